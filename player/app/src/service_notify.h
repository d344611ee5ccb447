#pragma once
// The systemd service protocol (sd_notify(3)) for board/ssao-player.service, `Type=notify`:
// READY=1 once the first frame is on the display, WATCHDOG=1 from the path that presents frames,
// STATUS= when the state changes, STOPPING=1 on the way out.
//
// The watchdog is fed only by frame_presented(), which the play loop calls after a present that
// succeeded: a loop that stops presenting starves it and systemd restarts the player, however
// healthy the rest of the process looks. frame_presented() runs every frame, so it neither
// allocates nor blocks: messages are fixed strings or formatted into a member buffer, sent on a
// socket opened once with MSG_DONTWAIT, and WATCHDOG=1 goes out at most every half interval of
// the monotonic time it is given (tests give it their own).
#include <array>
#include <chrono>
#include <cstddef>
#include <string>
#include <string_view>

#include <sys/socket.h>
#include <sys/un.h>

namespace app {

class ServiceNotifier {
 public:
  using Nanos = std::chrono::nanoseconds;

  struct Config {
    std::string socket;   // NOTIFY_SOCKET: a path, or '@' and an abstract name; empty: not a service
    Nanos watchdog{0};    // WatchdogSec as systemd passes it (WATCHDOG_USEC); 0: no watchdog
    std::string problem;  // a malformed variable, named with what was expected; empty: none
  };
  // NOTIFY_SOCKET, and the watchdog interval from sd_watchdog_enabled() (WATCHDOG_USEC, when
  // WATCHDOG_PID is unset or this process). Read once: the player does not re-read its environment.
  static Config from_environment();

  // Opens the socket; with an empty config every call does nothing. A socket that cannot be
  // opened, or the config's problem, is reported by error(); the calls then do what they still can.
  explicit ServiceNotifier(const Config& config);
  ServiceNotifier() : ServiceNotifier(from_environment()) {}
  ~ServiceNotifier();
  ServiceNotifier(const ServiceNotifier&) = delete;
  ServiceNotifier& operator=(const ServiceNotifier&) = delete;

  bool enabled() const { return fd_ >= 0; }
  const std::string& error() const { return error_; }
  Nanos watchdog() const { return watchdog_; }
  bool ready_sent() const { return ready_sent_; }

  // After a frame was presented, `now` on a monotonic clock. The first sends READY=1; later ones
  // send WATCHDOG=1 once at least half the watchdog interval has passed since the last one (or
  // since READY=1). A message the socket does not take now is sent on the next frame.
  void frame_presented(Nanos now);
  // STATUS=<text> when it differs from the last one sent (text is cut to the buffer's size).
  void state(std::string_view text);
  // STOPPING=1 and STATUS=stopping; nothing is sent after it.
  void stopping();

 private:
  bool send(const char* message, std::size_t length);

  int fd_ = -1;
  sockaddr_un address_{};
  socklen_t address_length_ = 0;
  std::string error_;
  Nanos watchdog_{0};
  bool ready_sent_ = false, stopped_ = false;
  Nanos last_ping_{0};
  // "STATUS=" and the text; status_length_ == 0: none sent yet.
  std::array<char, 128> status_{};
  std::size_t status_length_ = 0;
};

}  // namespace app
