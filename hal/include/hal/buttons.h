#pragma once
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "hal/clock.h"

namespace hal {

enum class ButtonAction : std::uint8_t { press, release, long_press, repeat };
std::string_view to_string(ButtonAction a);

struct ButtonEvent {
  std::uint8_t button = 0;  // index into the board's button list; Buttons::name() gives its name
  ButtonAction action = ButtonAction::press;
  Nanos time{0};  // CLOCK_MONOTONIC: when the debounced level settled, or when the deadline fell
};

// Timing applied to one button. Durations of zero switch the feature off.
struct ButtonTiming {
  Nanos debounce = std::chrono::milliseconds(20);
  Nanos long_press = std::chrono::milliseconds(800);
  Nanos repeat_delay{0};  // first Repeat this long after Press; 0 = no auto-repeat
  Nanos repeat_interval = std::chrono::milliseconds(150);
};

// Debounced buttons. fd() becomes readable when raw edges arrive or a timing deadline passes;
// the app then calls read(). read() never blocks, throws or allocates.
class Buttons {
 public:
  virtual ~Buttons() = default;
  virtual int fd() const = 0;
  virtual std::size_t count() const = 0;
  virtual std::string_view name(std::size_t button) const = 0;
  // Drains pending edges, advances the timing state to the clock's now and copies out up to
  // out.size() events, oldest first; the rest stay queued for the next call.
  virtual std::size_t read(std::span<ButtonEvent> out) = 0;
  // Events lost because read() was not called for so long that the queue (256 events) filled.
  // Repeats go first, then long presses, then presses of clicks already over; a Release that leaves
  // its button up is never lost, so no button is left looking held. Non-zero: the app's loop stalled.
  virtual std::size_t dropped() const = 0;
  // The last failure of a line while running (e.g. its chip was removed), naming the button and
  // the error; empty when none. The failed button is released and stops reporting.
  virtual const std::string& last_error() const = 0;
};

}  // namespace hal
