#include "control/server.h"

#include "base/errno_text.h"
#include "socket_address.h"

#include <grp.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>

namespace control {
namespace {

// Whether a player (this one before a restart, or another) still listens at `address`.
bool someone_listens(const sockaddr_un& address) {
  const base::UniqueFd probe(socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0));
  return probe && connect(probe.get(), reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0;
}

void send_reply(int fd, std::string_view reply) {
  send(fd, reply.data(), reply.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
}

// Replies and reads what the client sent, so that closing does not reset the connection (a socket
// closed with a message unread makes the peer's read fail, reply or not).
void refuse(int fd, std::string_view reply) {
  send_reply(fd, reply);
  char discard[64];
  while (recv(fd, discard, sizeof discard, MSG_DONTWAIT | MSG_TRUNC) > 0) {
  }
}

std::string describe(const Server::Peer& peer) {
  return "pid " + std::to_string(peer.pid) + ", uid " + std::to_string(peer.uid);
}

}  // namespace

Server::~Server() {
  if (listener_) unlink(path_.c_str());
}

bool Server::open(const std::string& path, const Limits& limits, std::string& error) {
  sockaddr_un address;
  if (!socket_address(path, address, error)) {
    error = "control: " + error;
    return false;
  }
  struct stat st {};
  if (lstat(path.c_str(), &st) == 0) {
    if (!S_ISSOCK(st.st_mode)) {
      error = "control: " + path + " exists and is not a socket; it is left as it is";
      return false;
    }
    if (someone_listens(address)) {
      error = "control: another player listens on " + path + " (give this one its own with --control PATH)";
      return false;
    }
    unlink(path.c_str());  // left by a player that is gone
  }
  base::UniqueFd fd(socket(AF_UNIX, SOCK_SEQPACKET | SOCK_NONBLOCK | SOCK_CLOEXEC, 0));
  if (!fd) {
    error = "control: no socket (" + base::errno_text(errno) + ")";
    return false;
  }
  if (bind(fd.get(), reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    error = "control: cannot make the socket " + path + " (" + base::errno_text(errno) + ")";
    return false;
  }
  // Connecting takes write permission: the owner and the control group, nobody else.
  chmod(path.c_str(), 0660);
  group control_group{}, *found = nullptr;
  char names[4096];
  has_control_group_ =
      getgrnam_r(std::string(kControlGroup).c_str(), &control_group, names, sizeof names, &found) == 0 && found != nullptr;
  if (has_control_group_) {
    control_gid_ = control_group.gr_gid;
    // Fails where the player is neither root nor in the group: then only root and its own user may.
    if (chown(path.c_str(), static_cast<uid_t>(-1), control_gid_) != 0) has_control_group_ = false;
  }
  if (listen(fd.get(), static_cast<int>(kMaxWaiting)) != 0) {
    error = "control: cannot listen on " + path + " (" + base::errno_text(errno) + ")";
    unlink(path.c_str());
    return false;
  }
  listener_ = std::move(fd);
  path_ = path;
  limits_ = limits;
  return true;
}

void Server::fds(std::vector<int>& out) const {
  if (!listener_) return;
  out.push_back(listener_.get());
  for (const Waiting& w : waiting_) out.push_back(w.fd.get());
}

bool Server::allowed(const base::UniqueFd& fd, Peer& peer) const {
  ucred credentials{};
  socklen_t length = sizeof credentials;
  if (getsockopt(fd.get(), SOL_SOCKET, SO_PEERCRED, &credentials, &length) != 0) return false;
  peer = {credentials.pid, credentials.uid};
  if (credentials.uid == 0 || credentials.uid == geteuid()) return true;
  if (!has_control_group_) return false;
  if (credentials.gid == control_gid_) return true;
  gid_t groups[256];
  length = sizeof groups;
  if (getsockopt(fd.get(), SOL_SOCKET, SO_PEERGROUPS, groups, &length) != 0) return false;
  const gid_t* begin = groups;
  const gid_t* end = begin + length / sizeof(gid_t);
  return std::find(begin, end, control_gid_) != end;
}

bool Server::take_token(double now_s) {
  if (!tokens_started_) {
    tokens_started_ = true;
    tokens_ = limits_.burst;
    tokens_at_s_ = now_s;
  }
  tokens_ = std::min<double>(limits_.burst, tokens_ + std::max(0.0, now_s - tokens_at_s_) * limits_.per_second);
  tokens_at_s_ = now_s;
  if (tokens_ < 1.0) return false;
  tokens_ -= 1.0;
  return true;
}

void Server::accept_all(double now_s, const std::function<void(const std::string&)>& log) {
  for (;;) {
    base::UniqueFd fd(accept4(listener_.get(), nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC));
    if (!fd) return;  // EAGAIN: none left (or an error the next poll shows again)
    Peer peer;
    std::string refusal;
    if (!allowed(fd, peer)) {
      refusal = "not allowed: " + describe(peer) + " is not root, not the player's user and not in the group " +
                std::string(kControlGroup);
      log("control: refused a connection, " + refusal);
    }
    if (waiting_.size() >= kMaxWaiting) {
      refuse(fd.get(),
             "error: " + (refusal.empty() ? "busy: " + std::to_string(kMaxWaiting) + " connections wait for their command already"
                                          : refusal));
      if (refusal.empty())
        log("control: refused a connection from " + describe(peer) + ": " + std::to_string(kMaxWaiting) +
            " connections wait already");
      continue;
    }
    waiting_.push_back({std::move(fd), peer, now_s, std::move(refusal)});
  }
}

void Server::answer_later(std::string_view reply) {
  for (const Waiting& w : later_) send_reply(w.fd.get(), reply);
  later_.clear();
}

void Server::serve(double now_s, const std::function<std::string(const Command&, const Peer&)>& handle,
                   const std::function<void(const std::string&)>& log) {
  if (!listener_) return;
  std::erase_if(later_, [&](const Waiting& w) {
    if (now_s - w.since_s <= limits_.reply_wait_s) return false;
    send_reply(w.fd.get(),
               "error: not done within " + std::to_string(static_cast<int>(limits_.reply_wait_s)) + " s (no frame was drawn)");
    log("control: a command from " + describe(w.peer) + " was not done within " +
        std::to_string(static_cast<int>(limits_.reply_wait_s)) + " s");
    return true;
  });
  accept_all(now_s, log);
  for (auto it = waiting_.begin(); it != waiting_.end();) {
    // MSG_TRUNC: the length of the whole message, so one too long is told apart from one that fits.
    const ssize_t n = recv(it->fd.get(), buffer_.data(), buffer_.size(), MSG_DONTWAIT | MSG_TRUNC);
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) {
      if (now_s - it->since_s <= limits_.message_wait_s) {
        ++it;
        continue;
      }
      if (!it->refusal.empty()) {
        send_reply(it->fd.get(), "error: " + it->refusal);
      } else {
        send_reply(it->fd.get(), "error: no command within " + std::to_string(static_cast<int>(limits_.message_wait_s)) + " s");
        log("control: closed a connection from " + describe(it->peer) + " that sent no command");
      }
    } else if (n > 0 && !it->refusal.empty()) {
      send_reply(it->fd.get(), "error: " + it->refusal);
    } else if (n > 0) {
      Command command;
      std::string error;
      const auto size = static_cast<std::size_t>(n);
      if (!take_token(now_s)) {
        send_reply(it->fd.get(), "error: too many commands (more than " + std::to_string(limits_.burst) + " at once, then " +
                                     std::to_string(limits_.per_second) + " a second): this one was ignored");
        log("control: ignored a command from " + describe(it->peer) + ": past the rate limit");
      } else if (!parse_command(std::string_view(buffer_.data(), std::min(size, buffer_.size())), command, error)) {
        // The buffer holds one byte more than a command may, so a longer one always fails; its
        // error names its whole length.
        if (size > kMaxMessage)
          error = "a command of " + std::to_string(size) + " bytes, more than " + std::to_string(kMaxMessage);
        send_reply(it->fd.get(), "error: " + error);
        log("control: refused a command from " + describe(it->peer) + ": " + error);
      } else {
        const std::string reply = handle(command, it->peer);
        if (reply.empty() && later_.size() < kMaxWaiting) {
          it->since_s = now_s;
          later_.push_back(std::move(*it));
        } else {
          send_reply(it->fd.get(), reply.empty() ? "error: busy: too many replies wait already" : reply);
        }
      }
    }
    // Answered, closed by the client, or failed: done with either way.
    it = waiting_.erase(it);
  }
}

}  // namespace control
