#pragma once
// The play session's clocks. Without --fps a headless run advances 1/30 s a frame on a manual
// clock, so a run is reproducible (the same frames, times and log); a run that shows frames on a
// display, or is paced by --fps, runs on the monotonic clock. The devices (buttons, LEDs, camera)
// run on the same clock as the playlist, so a scripted button lands on the same frame every run.
#include "hal/clock.h"

#include <chrono>

namespace app {

class PlayClock {
 public:
  using Steady = std::chrono::steady_clock;

  // `start`, `wall_start` and `manual_now`: where a session that lost its GPU context was, so the
  // next one plays on from there (see gpu_recovery.h); a first session starts them now and at 0.
  PlayClock(bool manual, Steady::time_point start, double wall_start, hal::Nanos manual_now)
      : manual_(manual), manual_clock_(manual_now), start_(start), wall_start_(wall_start) {}
  PlayClock(const PlayClock&) = delete;
  PlayClock& operator=(const PlayClock&) = delete;

  bool manual() const { return manual_; }
  // Seconds since the session (or the first one it continues) started, on the playlist's clock.
  double now() const { return manual_ ? std::chrono::duration<double>(manual_clock_.now()).count() : real_seconds(); }
  // Seconds since the start on the monotonic clock, whichever clock plays.
  double real_seconds() const { return std::chrono::duration<double>(Steady::now() - start_).count(); }
  // The Unix time the session started, for wallclock playlists.
  double wall_start() const { return wall_start_; }
  // The devices' clock.
  const hal::Clock& devices() const { return manual_ ? static_cast<const hal::Clock&>(manual_clock_) : monotonic_; }
  // Monotonic time for the service watchdog, which real time starves whatever clock plays.
  hal::Nanos monotonic() const { return monotonic_.now(); }
  // The manual clock moves on by a frame; the monotonic one moves by itself.
  void advance(double seconds) {
    if (manual_) manual_clock_.advance(std::chrono::duration_cast<hal::Nanos>(std::chrono::duration<double>(seconds)));
  }

  Steady::time_point start() const { return start_; }
  hal::Nanos manual_now() const { return manual_clock_.now(); }

 private:
  bool manual_;
  hal::ManualClock manual_clock_;
  hal::MonotonicClock monotonic_;
  Steady::time_point start_;
  double wall_start_;
};

inline double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace app
