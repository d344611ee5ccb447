#include "command_carrier.h"

#include "base/read_file.h"
#include "control/control.h"
#include "mqtt_link.h"
#include "screenshot.h"

#include <sys/eventfd.h>
#include <unistd.h>

namespace fleet {

CommandCarrier::CommandCarrier(const Config& config)
    : config_(config), wake_(eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK)), worker_([this] { work(); }) {}

CommandCarrier::~CommandCarrier() {
  {
    const std::lock_guard lock(mutex_);
    stop_ = true;
  }
  work_to_do_.notify_one();
  worker_.join();
}

void CommandCarrier::push(Message received) {
  {
    const std::lock_guard lock(mutex_);
    if (pending_.size() >= MqttLink::kMaxPending) {
      done_.push_back({pending_.front().topic,
                       pending_.front().payload,
                       pending_.front().topic,
                       "error: dropped unanswered: more than " + std::to_string(MqttLink::kMaxPending) + " commands waited",
                       {},
                       {}});
      pending_.pop_front();
      const std::uint64_t one = 1;
      (void)!write(wake_.get(), &one, sizeof one);
    }
    pending_.push_back(std::move(received));
  }
  work_to_do_.notify_one();
}

std::optional<CommandCarrier::Done> CommandCarrier::take() {
  const std::lock_guard lock(mutex_);
  std::uint64_t count = 0;
  while (read(wake_.get(), &count, sizeof count) > 0) {
  }
  if (done_.empty()) return std::nullopt;
  Done done = std::move(done_.front());
  done_.pop_front();
  return done;
}

void CommandCarrier::work() {
  std::unique_lock lock(mutex_);
  for (;;) {
    work_to_do_.wait(lock, [this] { return stop_ || !pending_.empty(); });
    if (stop_) return;
    const Message received = std::move(pending_.front());
    pending_.pop_front();
    lock.unlock();
    Done done = carry(received);
    lock.lock();
    done_.push_back(std::move(done));
    const std::uint64_t one = 1;
    (void)!write(wake_.get(), &one, sizeof one);
  }
}

CommandCarrier::Done CommandCarrier::carry(const Message& received) const {
  Done done{received.topic, received.payload, received.topic, {}, {}, {}};
  std::string error;
  if (!command_of(config_, received.topic, received.payload, done.command, error)) {
    done.command = received.topic;
    done.reply = "error: " + error;
    return done;
  }
  const bool screenshot = done.command == "screenshot";
  if (!control::send_command(config_.control, done.command, screenshot ? kScreenshotTimeoutMs : kReplyTimeoutMs, done.reply,
                             error)) {
    done.reply = "error: " + error;
    return done;
  }
  if (!screenshot || !control::reply_ok(done.reply)) return done;
  // "ok: frame N written to PATH[; camera frame written to PATH2]": each as a JPEG for its topic.
  const std::size_t max_bytes = static_cast<std::size_t>(config_.screenshot_max_kb) * base::kKiB;
  const auto encode = [&](std::string_view marker, std::string& jpeg, const char* what) {
    const std::size_t at = done.reply.find(marker);
    if (at == std::string::npos) return;
    const std::size_t start = at + marker.size(), end = done.reply.find(';', start);
    int width = 0, height = 0;
    if (!jpeg_within(done.reply.substr(start, end == std::string::npos ? std::string::npos : end - start), max_bytes, jpeg, width,
                     height, error)) {
      jpeg.clear();
      done.reply += std::string("; the ") + what + " cannot be sent: " + error;
    } else {
      done.reply += std::string("; ") + what + " sent as a " + std::to_string(width) + "x" + std::to_string(height) + " JPEG";
    }
  };
  encode(" written to ", done.jpeg, "frame");
  encode("; camera frame written to ", done.camera_jpeg, "camera frame");
  return done;
}

}  // namespace fleet
