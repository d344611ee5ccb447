#include "play/opening_schedule.h"

#include <chrono>
#include <cmath>

namespace app {
namespace {

hal::OpeningHours::Time to_time(double wall_s) {
  return hal::OpeningHours::Time(std::chrono::seconds(static_cast<long long>(std::floor(wall_s))));
}

}  // namespace

void OpeningSchedule::look(double wall_s, double monotonic_s) {
  const hal::OpeningHours::Time now = to_time(wall_s);
  const bool was_open = scheduled_open_;
  scheduled_open_ = hours_->open_at(now);
  next_change_ = hours_->next_change(now);
  next_look_s_ = monotonic_s + kLookEvery;
  // The hours changed under the command: it held until now.
  if (reported_ && scheduled_open_ != was_open) override_.reset();
}

bool OpeningSchedule::update(double wall_s, double monotonic_s) {
  if (hours_ != nullptr && (!reported_ || monotonic_s >= next_look_s_ || (next_change_ && to_time(wall_s) >= *next_change_)))
    look(wall_s, monotonic_s);
  const bool changed = !reported_ || on() != last_on_;
  reported_ = true;
  last_on_ = on();
  return changed;
}

std::string OpeningSchedule::command(bool on) {
  override_ = on;
  std::string reply = std::string("ok: display ") + (on ? "on" : "off");
  if (hours_ == nullptr) return reply + " (no opening hours: until the next display command)";
  if (on == scheduled_open_) {
    override_.reset();  // what the hours say anyway: nothing to hold
    return reply + " (as the opening hours have it)";
  }
  return reply + (next_change_ ? " until the opening hours change at " + hours_->local_text(*next_change_)
                               : " (the opening hours do not change again)");
}

std::string OpeningSchedule::describe() const {
  std::string text = override_ ? (*override_ ? "on by command" : "off by command") : (scheduled_open_ ? "open" : "closed");
  if (hours_ != nullptr && next_change_) text += " until " + hours_->local_text(*next_change_);
  return text;
}

}  // namespace app
