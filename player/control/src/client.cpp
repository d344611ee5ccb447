#include "base/errno_text.h"
#include "base/unique_fd.h"
#include "control/control.h"
#include "socket_address.h"

#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>

namespace control {
namespace {

using Clock = std::chrono::steady_clock;

int left_ms(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return left > 0 ? static_cast<int>(left) : 0;
}

}  // namespace

bool send_command(const std::string& path, std::string_view message, int timeout_ms, std::string& reply, std::string& error) {
  const Clock::time_point deadline = Clock::now() + std::chrono::milliseconds(timeout_ms);
  sockaddr_un address;
  if (!socket_address(path, address, error)) return false;
  base::UniqueFd fd(socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0));
  if (!fd) {
    error = "no socket (" + base::errno_text(errno) + ")";
    return false;
  }
  if (connect(fd.get(), reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    const int code = errno;
    error = path + ": " + base::errno_text(code);
    if (code == ENOENT || code == ECONNREFUSED)
      error += " (no player listens there: is it running, with --control or the board's control = \"" + path + "\"?)";
    else if (code == EACCES)
      error += " (run it as root, as the player's user, or as a member of the group " + std::string(kControlGroup) + ")";
    return false;
  }
  if (send(fd.get(), message.data(), message.size(), MSG_NOSIGNAL) < 0) {
    error = path + ": sending the command: " + base::errno_text(errno);
    return false;
  }
  char buffer[1024];
  for (;;) {
    pollfd wait{fd.get(), POLLIN, 0};
    const int ready = poll(&wait, 1, left_ms(deadline));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) {
      error = path + ": no reply within " + std::to_string(timeout_ms) + " ms (the player is busy or stuck)";
      return false;
    }
    const ssize_t n = recv(fd.get(), buffer, sizeof buffer, 0);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error = path + ": the player closed the connection without a reply" +
              (n < 0 ? " (" + base::errno_text(errno) + ")" : std::string());
      return false;
    }
    reply.assign(buffer, static_cast<std::size_t>(n));
    return true;
  }
}

}  // namespace control
