#!/usr/bin/env python3
"""A USB keyboard that types KEY... (board key names: space, n, c, p), made with uinput: the board's
keyboard buttons for tests in the VM. It appears, waits until process PID has opened its event node
(the player finds keyboards through inotify on /dev/input, once per loop), presses and releases each
key in turn, prints "typed", stays plugged in for SECONDS (--hold; until killed, if sooner), and
disappears.

    uinput_keys.py --reader PID [--hold SECONDS] KEY...

Hold it until the reader has acted: evdev refuses every read once its device is gone, events still
queued included, so a reader that polls once a frame loses keys typed less than a frame before the
keyboard goes (the guest's frames took over a second under load, and the pause never came).
"""
import fcntl
import os
import struct
import sys
import time

# linux/uinput.h and linux/input-event-codes.h
UI_SET_EVBIT = 0x40045564
UI_SET_KEYBIT = 0x40045565
UI_DEV_SETUP = 0x405C5503  # _IOW('U', 3, struct uinput_setup), 92 bytes
UI_DEV_CREATE = 0x5501
UI_DEV_DESTROY = 0x5502
UI_GET_SYSNAME_64 = 0x8040552C  # _IOC(_IOC_READ, 'U', 44, 64)
EV_SYN, EV_KEY, SYN_REPORT, BUS_USB = 0, 1, 0, 3
CODES = {"space": 57, "n": 49, "c": 46, "p": 25, "return": 28}


def main(argv):
    reader, hold = None, 0.5
    while len(argv) > 1 and argv[0] in ("--reader", "--hold"):
        if argv[0] == "--reader":
            reader = int(argv[1])
        else:
            hold = float(argv[1])
        argv = argv[2:]
    unknown = [k for k in argv if k not in CODES]
    if not argv or unknown:
        sys.exit(f"uinput_keys.py: expected keys among {', '.join(CODES)}, got {' '.join(unknown or ['nothing'])}")
    fd = os.open("/dev/uinput", os.O_WRONLY | os.O_NONBLOCK)
    fcntl.ioctl(fd, UI_SET_EVBIT, EV_KEY)
    for code in range(1, 128):  # a whole keyboard, letters included, as a USB keyboard reports
        fcntl.ioctl(fd, UI_SET_KEYBIT, code)
    fcntl.ioctl(fd, UI_DEV_SETUP, struct.pack("HHHH80sI", BUS_USB, 0x1D6B, 0x0104, 1, b"vm test keyboard", 0))
    fcntl.ioctl(fd, UI_DEV_CREATE)
    name = fcntl.ioctl(fd, UI_GET_SYSNAME_64, bytes(64)).split(b"\0")[0].decode()
    nodes = []
    for _ in range(600):  # up to 60 s: a sanitizer build under TCG runs a loop in about a second
        nodes = [f"/dev/input/{n}" for n in os.listdir(f"/sys/devices/virtual/input/{name}") if n.startswith("event")]
        if nodes:
            break
        time.sleep(0.1)
    if reader is None:
        time.sleep(2.0)
    else:
        for _ in range(600):
            fds = f"/proc/{reader}/fd"
            if any(os.path.realpath(os.path.join(fds, f)) in nodes for f in os.listdir(fds)):
                break
            time.sleep(0.1)
        else:
            sys.exit(f"uinput_keys.py: process {reader} did not open {' '.join(nodes) or name} within 60 s")

    def emit(kind, code, value):
        os.write(fd, struct.pack("llHHi", 0, 0, kind, code, value))

    for key in argv:
        for value in (1, 0):
            emit(EV_KEY, CODES[key], value)
            emit(EV_SYN, SYN_REPORT, 0)
            # Short: a key held past its button's long press (play: 800 ms) would be a long press.
            time.sleep(0.05)
    print("typed", " ".join(argv), flush=True)
    time.sleep(hold)
    fcntl.ioctl(fd, UI_DEV_DESTROY)
    os.close(fd)


if __name__ == "__main__":
    main(sys.argv[1:])
