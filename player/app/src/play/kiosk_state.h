#pragma once
// The kiosk's state as the board tells it (the status file, the LEDs, `systemctl status`), and the
// LED patterns that tell it (documented in board/README.md). Pure: the inputs are events and times
// (seconds on the play clock), the outputs the state and the LED plan; nothing here touches a
// device, GL or a file, so every transition is a unit test (tests/unit/kiosk_state_test.cpp).
#include "hal/status.h"

#include <cstdint>
#include <string_view>

namespace app {

class KioskState {
 public:
  // no_display: the platform has no display to show frames on (none connected, or another process
  // holds it); the playlist clock runs on and nothing is drawn. closed: outside the opening hours
  // (or `player ctl display off`): nothing is drawn and the display is off, as intended.
  enum class State : std::uint8_t { starting, loading, playing, paused, error, no_display, closed };
  // What a drawn frame showed: no item can play (every scene failed), the item's scene is still on
  // its way to the GPU, or the item's scene.
  enum class Shown : std::uint8_t { nothing_playable, loading, scene };

  // The status LED tells the state, the error LED problems.
  struct LedPlan {
    hal::LedPattern status = hal::LedPattern::off, error = hal::LedPattern::off;
    bool operator==(const LedPlan&) const = default;
  };

  State state() const { return state_; }
  std::string_view name() const;

  // Transitions; each returns true when the state changed, so the status goes out at once.
  // The display went away (or was never there at start): no display, whatever was before.
  bool display_lost();
  // The opening hours closed (or a command switched the display off): closed, whatever was before,
  // until a frame is drawn again.
  bool closed();
  // A frame was drawn showing `shown`, with the playlist clock `paused` (a button): playing, paused
  // (only a scene is paused), loading or error. A display that came back leaves no display here.
  bool frame_drawn(Shown shown, bool paused);
  // The player stops: a run that ended starting, loading or paused reports playing (what it did);
  // error, no display and closed stay, since they are what a monitor must still see.
  bool stopped();

  // Warnings, which only the error LED shows.
  // An error was reported at `now`: the error LED blinks slowly for kErrorShownFor seconds.
  void error_reported(double now);
  // Whether something that lasts is being warned of (a device missing since start, the camera lost,
  // content drawn with warnings): the error LED blinks slowly while it holds.
  void set_lasting_warning(bool present) { lasting_warning_ = present; }
  // A display self-check's verdict: a failed one blinks the error LED fast until one passes.
  void check_finished(bool passed) { check_failed_ = !passed; }

  // The LEDs at `now`.
  LedPlan leds(double now) const;

  static constexpr double kErrorShownFor = 60.0;

 private:
  State state_ = State::starting;
  bool lasting_warning_ = false, check_failed_ = false, error_seen_ = false;
  double last_error_s_ = 0.0;
};

std::string_view name(KioskState::State state);
// The patterns for a state: `warning` blinks the error LED slowly, `check_failed` fast; in the error
// state the error LED is on and the status LED off.
KioskState::LedPlan led_plan(KioskState::State state, bool warning, bool check_failed);

}  // namespace app
