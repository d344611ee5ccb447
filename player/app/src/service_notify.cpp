#include "service_notify.h"

#include <systemd/sd-daemon.h>

#include <algorithm>
#include <cerrno>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>

#include <unistd.h>

namespace app {

ServiceNotifier::Config ServiceNotifier::from_environment() {
  Config config;
  if (const char* socket = std::getenv("NOTIFY_SOCKET")) config.socket = socket;
  std::uint64_t usec = 0;
  const int watchdog = sd_watchdog_enabled(0, &usec);
  if (watchdog > 0) {
    config.watchdog = std::chrono::microseconds(usec);
  } else if (watchdog < 0) {
    const char* value = std::getenv("WATCHDOG_USEC");
    const char* pid = std::getenv("WATCHDOG_PID");
    config.problem = "WATCHDOG_USEC='" + std::string(value != nullptr ? value : "") + "', WATCHDOG_PID='" +
                     std::string(pid != nullptr ? pid : "") +
                     "': expected microseconds above 0 and this process's id; the watchdog is not fed (" +
                     std::strerror(-watchdog) + ")";
  }
  return config;
}

ServiceNotifier::ServiceNotifier(const Config& config) : error_(config.problem), watchdog_(config.watchdog) {
  if (config.socket.empty()) return;
  // sd_notify(3): an absolute path, or '@' for Linux's abstract namespace (a leading NUL).
  const std::string& name = config.socket;
  const bool abstract = name[0] == '@';
  if ((!abstract && name[0] != '/') || name.size() < 2 || name.size() >= sizeof address_.sun_path) {
    error_ = "NOTIFY_SOCKET='" + name + "': expected an absolute path or '@' and an abstract name, shorter than " +
             std::to_string(sizeof address_.sun_path) + " bytes; systemd is not told the player is ready";
    return;
  }
  address_.sun_family = AF_UNIX;
  std::memcpy(address_.sun_path, name.data(), name.size());
  if (abstract) address_.sun_path[0] = '\0';
  // An abstract name's length is the address's length, with no terminating NUL.
  address_length_ = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + name.size() + (abstract ? 0 : 1));
  fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd_ < 0) error_ = "NOTIFY_SOCKET='" + name + "': cannot open a datagram socket (" + std::strerror(errno) + ")";
}

ServiceNotifier::~ServiceNotifier() {
  if (fd_ >= 0) close(fd_);
}

bool ServiceNotifier::send(const char* message, std::size_t length) {
  // Addressed on every send rather than connected once: a manager that re-creates its socket
  // (daemon-reexec) is still reached. MSG_DONTWAIT: a full queue drops the message, never the frame.
  const ssize_t sent =
      sendto(fd_, message, length, MSG_DONTWAIT | MSG_NOSIGNAL, reinterpret_cast<const sockaddr*>(&address_), address_length_);
  return sent == static_cast<ssize_t>(length);
}

void ServiceNotifier::frame_presented(Nanos now) {
  if (fd_ < 0 || stopped_) return;
  if (!ready_sent_) {
    static constexpr char kReady[] = "READY=1";
    if (send(kReady, sizeof kReady - 1)) {
      ready_sent_ = true;
      last_ping_ = now;  // systemd starts the watchdog's timer at READY=1
    }
    return;
  }
  if (watchdog_ <= Nanos{0} || now - last_ping_ < watchdog_ / 2) return;
  static constexpr char kPing[] = "WATCHDOG=1";
  if (send(kPing, sizeof kPing - 1)) last_ping_ = now;
}

void ServiceNotifier::state(std::string_view text) {
  if (fd_ < 0 || stopped_) return;
  static constexpr std::string_view kKey = "STATUS=";
  const std::size_t length = kKey.size() + std::min(text.size(), status_.size() - kKey.size());
  if (length == status_length_ && std::memcmp(status_.data() + kKey.size(), text.data(), length - kKey.size()) == 0) return;
  std::memcpy(status_.data(), kKey.data(), kKey.size());
  std::memcpy(status_.data() + kKey.size(), text.data(), length - kKey.size());
  // Not taken: forget it, so the next call with the same state tries again.
  status_length_ = send(status_.data(), length) ? length : 0;
}

void ServiceNotifier::stopping() {
  if (fd_ < 0 || stopped_) return;
  static constexpr char kStopping[] = "STOPPING=1\nSTATUS=stopping";
  send(kStopping, sizeof kStopping - 1);
  stopped_ = true;
}

}  // namespace app
