#!/usr/bin/env python3
"""A USB keyboard that types KEY... (board key names: space, n, c, p), made with uinput: the board's
keyboard buttons for tests in the VM. It appears, waits for the player to find it (inotify on
/dev/input), presses and releases each key in turn, and disappears.

    uinput_keys.py [--settle SECONDS] KEY...
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
EV_SYN, EV_KEY, SYN_REPORT, BUS_USB = 0, 1, 0, 3
CODES = {"space": 57, "n": 49, "c": 46, "p": 25, "return": 28}


def main(argv):
    settle = 2.0
    if len(argv) > 1 and argv[0] == "--settle":
        settle, argv = float(argv[1]), argv[2:]
    unknown = [k for k in argv if k not in CODES]
    if not argv or unknown:
        sys.exit(f"uinput_keys.py: expected keys among {', '.join(CODES)}, got {' '.join(unknown or ['nothing'])}")
    fd = os.open("/dev/uinput", os.O_WRONLY | os.O_NONBLOCK)
    fcntl.ioctl(fd, UI_SET_EVBIT, EV_KEY)
    for code in range(1, 128):  # a whole keyboard, letters included, as a USB keyboard reports
        fcntl.ioctl(fd, UI_SET_KEYBIT, code)
    fcntl.ioctl(fd, UI_DEV_SETUP, struct.pack("HHHH80sI", BUS_USB, 0x1D6B, 0x0104, 1, b"vm test keyboard", 0))
    fcntl.ioctl(fd, UI_DEV_CREATE)
    time.sleep(settle)

    def emit(kind, code, value):
        os.write(fd, struct.pack("llHHi", 0, 0, kind, code, value))

    for key in argv:
        for value in (1, 0):
            emit(EV_KEY, CODES[key], value)
            emit(EV_SYN, SYN_REPORT, 0)
            # Short: a key held past its button's long press (play: 800 ms) would be a long press.
            time.sleep(0.05)
    time.sleep(0.5)
    fcntl.ioctl(fd, UI_DEV_DESTROY)
    os.close(fd)


if __name__ == "__main__":
    main(sys.argv[1:])
