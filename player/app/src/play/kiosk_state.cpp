#include "play/kiosk_state.h"

namespace app {

using State = KioskState::State;

std::string_view name(State state) {
  switch (state) {
    case State::starting:
      return "starting";
    case State::loading:
      return "loading";
    case State::playing:
      return "playing";
    case State::paused:
      return "paused";
    case State::error:
      return "error";
    case State::no_display:
      return "no display";
    case State::closed:
      return "closed";
  }
  return "?";
}

KioskState::LedPlan led_plan(State state, bool warning, bool check_failed) {
  KioskState::LedPlan plan;
  switch (state) {
    case State::starting:
      plan.status = hal::LedPattern::blink_fast;
      break;
    case State::loading:
      plan.status = hal::LedPattern::blink_slow;
      break;
    case State::playing:
      plan.status = hal::LedPattern::heartbeat;
      break;
    case State::paused:
      plan.status = hal::LedPattern::on;
      break;
    case State::error:
      plan.error = hal::LedPattern::on;
      break;
    case State::no_display:
      plan.status = hal::LedPattern::blink_slow;
      break;
    case State::closed:
      plan.status = hal::LedPattern::standby;
      break;
  }
  if (state != State::error)
    plan.error = check_failed ? hal::LedPattern::blink_fast : warning ? hal::LedPattern::blink_slow : hal::LedPattern::off;
  return plan;
}

std::string_view KioskState::name() const {
  return app::name(state_);
}

namespace {
bool change(State& state, State to) {
  const bool changed = state != to;
  state = to;
  return changed;
}
}  // namespace

bool KioskState::display_lost() {
  return change(state_, State::no_display);
}

bool KioskState::closed() {
  return change(state_, State::closed);
}

bool KioskState::frame_drawn(Shown shown, bool paused) {
  State to = State::playing;
  switch (shown) {
    case Shown::nothing_playable:
      to = State::error;
      break;
    case Shown::loading:
      to = State::loading;
      break;
    case Shown::scene:
      to = paused ? State::paused : State::playing;
      break;
  }
  return change(state_, to);
}

bool KioskState::stopped() {
  if (state_ == State::error || state_ == State::no_display || state_ == State::closed) return false;
  return change(state_, State::playing);
}

void KioskState::error_reported(double now) {
  error_seen_ = true;
  last_error_s_ = now;
}

KioskState::LedPlan KioskState::leds(double now) const {
  const bool recent_error = error_seen_ && now - last_error_s_ < kErrorShownFor;
  return led_plan(state_, lasting_warning_ || recent_error, check_failed_);
}

}  // namespace app
