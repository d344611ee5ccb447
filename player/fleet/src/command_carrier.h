#pragma once
// Commands from the broker carried to the player's control socket on a thread of their own, one at
// a time: a player slow to answer (a screenshot waits for its next frame; a board under load) must
// not keep the agent from the broker, whose keepalive would otherwise call it gone.
#include "base/unique_fd.h"
#include "fleet/fleet.h"

#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>
#include <thread>

namespace fleet {

class CommandCarrier {
 public:
  struct Done {
    std::string topic, payload;  // as received
    std::string command;         // the control message sent, or the topic when it was not one
    std::string reply;           // the player's, or "error: why"
    std::string jpeg;            // after a screenshot: the frame, within screenshot_max_kb
    std::string camera_jpeg;     // and what the check camera saw, where the board has one
  };

  explicit CommandCarrier(const Config& config);
  ~CommandCarrier();
  CommandCarrier(const CommandCarrier&) = delete;
  CommandCarrier& operator=(const CommandCarrier&) = delete;

  // At most MqttLink::kMaxPending wait; beyond that the oldest is dropped (and answered as such).
  void push(Message received);
  std::optional<Done> take();
  // Readable while a Done waits (an eventfd): the agent's poll wakes for it.
  int fd() const { return wake_.get(); }

  // How long the player may take: it answers in its next poll (a frame at most), a screenshot after
  // its next frame is drawn and read back.
  static constexpr int kReplyTimeoutMs = 10000, kScreenshotTimeoutMs = 20000;

 private:
  void work();
  Done carry(const Message& received) const;

  const Config& config_;
  std::mutex mutex_;
  std::condition_variable work_to_do_;
  base::UniqueFd wake_;
  std::deque<Message> pending_;
  std::deque<Done> done_;
  bool stop_ = false;
  std::thread worker_;  // last: started once everything above is made
};

}  // namespace fleet
