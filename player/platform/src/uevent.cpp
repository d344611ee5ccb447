#include "uevent.h"

#include <linux/netlink.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace platform::uevent {

bool parse(std::span<const char> bytes, Message& out) {
  out = {};
  const std::string_view all(bytes.data(), bytes.size());
  const size_t first_end = all.find('\0');
  const std::string_view header = all.substr(0, first_end);
  if (header.find('@') == std::string_view::npos || header.rfind("libudev", 0) == 0) return false;
  size_t at = first_end == std::string_view::npos ? all.size() : first_end + 1;
  while (at < all.size()) {
    size_t end = all.find('\0', at);
    if (end == std::string_view::npos) end = all.size();
    const std::string_view field = all.substr(at, end - at);
    const size_t equals = field.find('=');
    if (equals != std::string_view::npos) {
      const std::string_view key = field.substr(0, equals), value = field.substr(equals + 1);
      if (key == "ACTION")
        out.action = value;
      else if (key == "SUBSYSTEM")
        out.subsystem = value;
      else if (key == "DEVNAME")
        out.devname = value;
      else if ((key == "HOTPLUG" || key == "SYNTH_ARG_HOTPLUG") && value == "1")
        out.hotplug = true;
    }
    at = end + 1;
  }
  return !out.action.empty();
}

bool is_drm_change_of(const Message& message, std::string_view device_path) {
  if (message.subsystem != "drm" || message.action != "change") return false;
  // DEVNAME is relative to /dev ("dri/card0"); older kernels sent the absolute path.
  std::string_view devname = message.devname;
  if (devname.rfind("/dev/", 0) == 0) devname.remove_prefix(5);
  std::string_view path = device_path;
  if (path.rfind("/dev/", 0) == 0) path.remove_prefix(5);
  return !devname.empty() && devname == path;
}

int open_socket() {
  const int fd = socket(AF_NETLINK, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, NETLINK_KOBJECT_UEVENT);
  if (fd < 0) return -1;
  sockaddr_nl address;
  std::memset(&address, 0, sizeof address);
  address.nl_family = AF_NETLINK;
  address.nl_groups = 1;  // the kernel's own broadcast group (udev's is 2)
  // The socket hears every device's events; room for a burst (a USB hub plugged in) so that a
  // display's is not the one dropped. Lost events are noticed (ENOBUFS) and the connectors read anyway.
  const int receive_buffer = 1 << 20;
  setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &receive_buffer, sizeof receive_buffer);
  if (bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) {
    const int saved = errno;
    close(fd);
    errno = saved;
    return -1;
  }
  return fd;
}

}  // namespace platform::uevent
