#pragma once
// Time source for the hardware layer. Every timestamp hal hands out is CLOCK_MONOTONIC nanoseconds,
// the clock the kernel stamps GPIO edge events with, so kernel and user-space times compare directly.
#include <chrono>
#include <cstdint>

namespace hal {

using Nanos = std::chrono::nanoseconds;

class Clock {
 public:
  virtual ~Clock() = default;
  virtual Nanos now() const = 0;
};

// The real monotonic clock.
class MonotonicClock final : public Clock {
 public:
  Nanos now() const override;
};

// A clock only the test moves, so debounce, long press and LED timing are checked without sleeping.
class ManualClock final : public Clock {
 public:
  explicit ManualClock(Nanos start = Nanos{0}) : now_(start) {}
  Nanos now() const override { return now_; }
  void set(Nanos t) { now_ = t; }
  void advance(Nanos d) { now_ += d; }

 private:
  Nanos now_;
};

}  // namespace hal
