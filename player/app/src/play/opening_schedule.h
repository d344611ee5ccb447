#pragma once
// Whether the display is on: the board's opening hours (hal::OpeningHours), overridden by
// `player ctl display on|off` until the hours next change. Pure: the inputs are the wall time (the
// play clock's, so a manual-clock run previews a schedule) and the monotonic time; the loop asks
// once per pass, and the hours are read again only at their next change or a minute after the
// last look (a clock set by NTP after boot moves the wall time under a schedule).
#include "hal/opening_hours.h"

#include <optional>
#include <string>

namespace app {

class OpeningSchedule {
 public:
  // `hours`: none for always open. Kept by pointer: the board config outlives the loop.
  explicit OpeningSchedule(const hal::OpeningHours* hours) : hours_(hours) {}

  // Looks at the hours when due; true when whether the display should be on changed (the first
  // call always reports a change, so the loop sets the display up from it).
  bool update(double wall_s, double monotonic_s);
  bool on() const { return override_ ? *override_ : scheduled_open_; }
  // `player ctl display on|off`: holds until the hours next change (with no hours: until the next
  // command). Returns the reply.
  std::string command(bool on);
  // "open until 2026-12-08 18:00 CET", "closed until ...", "on by command until ...", for the log and
  // the status file; "open" without hours.
  std::string describe() const;

 private:
  void look(double wall_s, double monotonic_s);

  const hal::OpeningHours* hours_;
  bool scheduled_open_ = true, reported_ = false, last_on_ = true;
  std::optional<bool> override_;
  std::optional<hal::OpeningHours::Time> next_change_;
  double next_look_s_ = -1.0;  // monotonic
  static constexpr double kLookEvery = 60.0;
};

}  // namespace app
