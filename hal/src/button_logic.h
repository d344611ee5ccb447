#pragma once
// Debounce, long press and auto-repeat as a pure state machine over (level, time) inputs, shared by
// the GPIO and mock buttons so both behave identically and tests drive it with a manual clock.
#include <array>
#include <span>
#include <vector>

#include "hal/buttons.h"

namespace hal::detail {

class ButtonLogic {
 public:
  // At most kMaxButtons buttons (ButtonEvent::button is 8 bits); throws std::invalid_argument otherwise.
  explicit ButtonLogic(std::vector<ButtonTiming> timing);
  static constexpr std::size_t kMaxButtons = 255;

  // The initial debounced level, without an event (a button held at start-up is not a press).
  void set_initial(std::size_t button, bool pressed);
  // A raw level change at `t`. Deadlines before `t` are processed first so events stay in order.
  void edge(std::size_t button, bool pressed, Nanos t);
  // Emits every event due at or before `now`, in time order.
  void advance(Nanos now);
  // The earliest pending deadline, Nanos::max() when none.
  Nanos next_deadline() const;
  std::size_t drain(std::span<ButtonEvent> out);
  std::size_t dropped() const { return dropped_; }

 private:
  struct State {
    ButtonTiming timing;
    bool raw = false;
    Nanos raw_since{0};
    bool settle_pending = false;
    bool stable = false;
    Nanos pressed_at{0};
    bool long_sent = false;
    Nanos next_repeat = Nanos::max();
  };
  Nanos deadline(const State& s) const;
  void fire(std::size_t button, State& s);
  void push(std::size_t button, ButtonAction a, Nanos t);
  void evict_one();

  std::vector<State> states_;
  // A fixed ring so the event path never allocates. The app reads every poll cycle, so it fills only
  // when the app stalls for seconds; then push() evicts the least useful event (evict_one(), counted
  // in dropped_), never a Release that leaves its button up: a lost Release would leave the app
  // believing the button is still held. One slot more than there can be buttons means a full queue
  // always holds something else to drop.
  std::array<ButtonEvent, kMaxButtons + 1> queue_{};
  std::size_t head_ = 0;
  std::size_t size_ = 0;
  std::size_t dropped_ = 0;
};

}  // namespace hal::detail
