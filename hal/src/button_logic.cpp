#include "button_logic.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "base/names.h"

namespace hal {

namespace {
constexpr base::Name<ButtonAction> kButtonActionNames[] = {{ButtonAction::press, "press"},
                                                           {ButtonAction::release, "release"},
                                                           {ButtonAction::long_press, "long-press"},
                                                           {ButtonAction::repeat, "repeat"}};
static_assert(base::in_enum_order(kButtonActionNames));
}  // namespace

std::string_view to_string(ButtonAction a) {
  return base::name_of(kButtonActionNames, a);
}

namespace detail {

ButtonLogic::ButtonLogic(std::vector<ButtonTiming> timing) {
  if (timing.size() > kMaxButtons)
    throw std::invalid_argument("buttons: expected at most " + std::to_string(kMaxButtons) + ", got " +
                                std::to_string(timing.size()));
  states_.resize(timing.size());
  for (std::size_t i = 0; i < timing.size(); ++i) states_[i].timing = timing[i];
}

void ButtonLogic::set_initial(std::size_t button, bool pressed) {
  State& s = states_[button];
  s.raw = s.stable = pressed;
  s.settle_pending = false;
  // Held at start-up: no long press or repeat either, until it is released and pressed again.
  s.long_sent = true;
  s.next_repeat = Nanos::max();
}

Nanos ButtonLogic::deadline(const State& s) const {
  Nanos d = Nanos::max();
  if (s.settle_pending) d = s.raw_since + s.timing.debounce;
  if (s.stable) {
    if (!s.long_sent && s.timing.long_press.count() > 0) d = std::min(d, s.pressed_at + s.timing.long_press);
    d = std::min(d, s.next_repeat);
  }
  return d;
}

Nanos ButtonLogic::next_deadline() const {
  Nanos d = Nanos::max();
  for (const State& s : states_) d = std::min(d, deadline(s));
  return d;
}

void ButtonLogic::edge(std::size_t button, bool pressed, Nanos t) {
  advance(t - Nanos(1));  // a deadline exactly at the edge loses to the edge: the level moved
  State& s = states_[button];
  s.raw = pressed;
  s.raw_since = t;
  s.settle_pending = true;
  if (s.timing.debounce.count() == 0) fire(button, s);
}

void ButtonLogic::fire(std::size_t button, State& s) {
  const Nanos settle = s.raw_since + s.timing.debounce;
  if (s.settle_pending && settle <= deadline(s)) {
    s.settle_pending = false;
    if (s.raw == s.stable) return;  // bounced back to where it was: nothing happened
    s.stable = s.raw;
    if (s.stable) {
      s.pressed_at = s.raw_since;
      s.long_sent = false;
      s.next_repeat = s.timing.repeat_delay.count() > 0 ? s.pressed_at + s.timing.repeat_delay : Nanos::max();
      push(button, ButtonAction::press, s.raw_since);
    } else {
      s.next_repeat = Nanos::max();
      push(button, ButtonAction::release, s.raw_since);
    }
    return;
  }
  const Nanos long_at = s.pressed_at + s.timing.long_press;
  if (!s.long_sent && s.timing.long_press.count() > 0 && long_at <= s.next_repeat) {
    s.long_sent = true;
    push(button, ButtonAction::long_press, long_at);
    return;
  }
  push(button, ButtonAction::repeat, s.next_repeat);
  s.next_repeat += std::max(s.timing.repeat_interval, Nanos(std::chrono::milliseconds(1)));
}

void ButtonLogic::advance(Nanos now) {
  for (;;) {
    std::size_t best = states_.size();
    Nanos best_time = Nanos::max();
    for (std::size_t i = 0; i < states_.size(); ++i) {
      const Nanos d = deadline(states_[i]);
      if (d < best_time) {
        best_time = d;
        best = i;
      }
    }
    if (best == states_.size() || best_time > now) return;
    fire(best, states_[best]);
  }
}

void ButtonLogic::push(std::size_t button, ButtonAction a, Nanos t) {
  if (size_ == queue_.size()) evict_one();
  queue_[(head_ + size_) % queue_.size()] = ButtonEvent{static_cast<std::uint8_t>(button), a, t};
  ++size_;
}

void ButtonLogic::evict_one() {
  const std::size_t n = queue_.size();
  auto at = [&](std::size_t i) -> ButtonEvent& { return queue_[(head_ + i) % n]; };
  // The cheapest loss first, the oldest of each kind:
  //   a Repeat (another follows while the button is held), then a LongPress;
  //   a Press whose Release is queued too (a whole click, already over);
  //   a Release followed by another of its button with no Press between (the later one says the same);
  //   last, a Press of a button still held.
  // A Release that leaves its button up is never dropped. The last two passes run from the back to
  // know what follows each event; none allocates.
  constexpr std::size_t none = kMaxButtons + 1;
  std::size_t repeat = none, long_press = none, click = none, repeated_release = none, press = none;
  std::array<bool, kMaxButtons + 1> next_is_release{};  // of the events after i, per button
  for (std::size_t i = size_; i-- > 0;) {
    const ButtonEvent& e = at(i);
    switch (e.action) {
      case ButtonAction::repeat:
        repeat = i;
        break;
      case ButtonAction::long_press:
        long_press = i;
        break;
      case ButtonAction::press:
        if (next_is_release[e.button]) click = i;
        press = i;
        next_is_release[e.button] = false;
        break;
      case ButtonAction::release:
        if (next_is_release[e.button]) repeated_release = i;
        next_is_release[e.button] = true;
        break;
    }
  }
  std::size_t victim = none;
  for (const std::size_t candidate : {repeat, long_press, click, repeated_release, press})
    if (victim == none) victim = candidate;
  if (victim == none) victim = 0;  // unreachable: a full queue of Releases repeats some button's (see queue_)
  for (std::size_t i = victim; i + 1 < size_; ++i) at(i) = at(i + 1);
  --size_;
  ++dropped_;
}

std::size_t ButtonLogic::drain(std::span<ButtonEvent> out) {
  const std::size_t n = std::min(out.size(), size_);
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = queue_[head_];
    head_ = (head_ + 1) % queue_.size();
  }
  size_ -= n;
  return n;
}

}  // namespace detail
}  // namespace hal
