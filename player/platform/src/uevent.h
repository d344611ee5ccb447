#pragma once
// Kernel uevents for DRM hotplug, read from a NETLINK_KOBJECT_UEVENT socket: the kernel sends
// "change@/devices/.../drm/card0\0ACTION=change\0SUBSYSTEM=drm\0DEVNAME=dri/card0\0HOTPLUG=1\0...".
// Parsing is pure and allocates nothing, so it is tested on byte strings.
#include <span>
#include <string_view>

namespace platform::uevent {

struct Message {
  std::string_view action;     // "change", "add", "remove"
  std::string_view subsystem;  // "drm"
  std::string_view devname;    // "dri/card0", relative to /dev
  bool hotplug = false;        // HOTPLUG=1, or SYNTH_ARG_HOTPLUG=1 from a synthetic event written to sysfs
};

// False for what is not a kernel uevent (udev's own re-broadcasts start with "libudev").
bool parse(std::span<const char> bytes, Message& out);

// True when `message` is a hotplug (or any change) of the DRM device at `device_path` ("/dev/dri/card0").
bool is_drm_change_of(const Message& message, std::string_view device_path);

// A non-blocking, close-on-exec socket bound to the kernel's uevent group; -1 on failure (errno set).
int open_socket();

}  // namespace platform::uevent
