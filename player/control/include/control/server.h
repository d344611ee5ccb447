#pragma once
// The player's end of the control socket. open() binds and listens; the play loop polls fds() with
// its other sources and calls serve() when any is readable. Nothing here blocks: a connection whose
// message has not arrived yet waits in a short list (polled too) and is dropped after a while.
#include "base/unique_fd.h"
#include "control/control.h"

#include <sys/types.h>

#include <array>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace control {

class Server {
 public:
  struct Limits {
    int burst = 10;               // commands at once
    int per_second = 2;           // and then this many a second
    double message_wait_s = 2.0;  // a connection that sends nothing in this time is closed
    double reply_wait_s = 30.0;   // a reply put off (see serve) and not given in this time: an error
  };
  static constexpr std::size_t kMaxWaiting = 8;  // connections beyond these are refused at once

  Server() = default;
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;
  ~Server();  // removes the socket file

  // Binds the socket at `path` (mode 0660; group ssao-player-control where it exists and may be
  // given) and listens. A socket file left by a player that is gone is replaced; one a live
  // player listens on, or a file that is not a socket, is an error. False and why.
  bool open(const std::string& path, const Limits& limits, std::string& error);
  bool is_open() const { return listener_.get() >= 0; }
  const std::string& path() const { return path_; }

  // The listener and the connections waiting for their message, to poll for reading.
  void fds(std::vector<int>& out) const;

  // Who may command: root, the player's own user, members of ssao-player-control.
  struct Peer {
    pid_t pid = 0;
    uid_t uid = 0;
  };
  // Runs every pending command: `handle` does it and returns the reply ("ok..." or "error: ..."), or
  // an empty text to reply later with answer_later() (a screenshot waits for the next frame).
  // Refusals (a peer not allowed, a malformed or oversized message, a burst past the rate) are
  // replied to here and given to `log`, one line each, without reaching `handle`. `now_s`: a
  // monotonic clock in seconds.
  void serve(double now_s, const std::function<std::string(const Command&, const Peer&)>& handle,
             const std::function<void(const std::string&)>& log);
  // Replies to every command whose reply was put off, and closes their connections.
  void answer_later(std::string_view reply);
  bool answers_pending() const { return !later_.empty(); }
  // Connections still to be read or answered: serve() has their timeouts to keep even when no fd is ready.
  bool has_connections() const { return !waiting_.empty() || !later_.empty(); }

 private:
  struct Waiting {
    base::UniqueFd fd;
    Peer peer;
    double since_s = 0.0;
    // A peer not allowed: its message is read (closing with it unread would reset the connection,
    // and the client would see no reply) and answered with this.
    std::string refusal;
  };
  void accept_all(double now_s, const std::function<void(const std::string&)>& log);
  bool allowed(const base::UniqueFd& fd, Peer& peer) const;
  bool take_token(double now_s);

  base::UniqueFd listener_;
  std::string path_;
  Limits limits_;
  gid_t control_gid_ = 0;
  bool has_control_group_ = false;
  std::vector<Waiting> waiting_;
  std::vector<Waiting> later_;  // answered by answer_later(); not polled (a closed client reads as ready)
  double tokens_ = 0.0, tokens_at_s_ = 0.0;
  bool tokens_started_ = false;
  std::array<char, kMaxMessage + 1> buffer_{};
};

}  // namespace control
