// The kiosk's states and LED patterns as a person at the board sees them (board/README.md): the
// status file's `state`, the status LED, the error LED. Every transition from every state, and the
// LED plan of every state with and without warnings, a failed self-check or both.
#include "play/kiosk_state.h"

#include <gtest/gtest.h>

#include <array>

namespace {

using app::KioskState;
using State = KioskState::State;
using Shown = KioskState::Shown;
using hal::LedPattern;

constexpr std::array<State, 7> kStates = {State::starting, State::loading,    State::playing, State::paused,
                                          State::error,    State::no_display, State::closed};

// A kiosk in `state`, reached the way the player reaches it.
KioskState in(State state) {
  KioskState kiosk;
  switch (state) {
    case State::starting:
      break;
    case State::loading:
      kiosk.frame_drawn(Shown::loading, false);
      break;
    case State::playing:
      kiosk.frame_drawn(Shown::scene, false);
      break;
    case State::paused:
      kiosk.frame_drawn(Shown::scene, true);
      break;
    case State::error:
      kiosk.frame_drawn(Shown::nothing_playable, false);
      break;
    case State::no_display:
      kiosk.display_lost();
      break;
    case State::closed:
      kiosk.closed();
      break;
  }
  EXPECT_EQ(kiosk.state(), state);
  return kiosk;
}

TEST(KioskState, ThePlayerStartsInStarting) {
  const KioskState kiosk;
  EXPECT_EQ(kiosk.state(), State::starting);
  EXPECT_EQ(kiosk.name(), "starting");
}

TEST(KioskState, TheStatusFileNamesEveryState) {
  EXPECT_EQ(app::name(State::starting), "starting");
  EXPECT_EQ(app::name(State::loading), "loading");
  EXPECT_EQ(app::name(State::playing), "playing");
  EXPECT_EQ(app::name(State::paused), "paused");
  EXPECT_EQ(app::name(State::error), "error");
  EXPECT_EQ(app::name(State::no_display), "no display");
  EXPECT_EQ(app::name(State::closed), "closed");
}

// One event from every state: where it lands, and whether the status goes out at once.
void expect_transitions(const char* event, auto&& apply, auto&& expected) {
  for (State from : kStates) {
    KioskState kiosk = in(from);
    const State to = expected(from);
    const bool changed = apply(kiosk);
    EXPECT_EQ(kiosk.state(), to) << event << " from " << app::name(from);
    EXPECT_EQ(changed, to != from) << event << " from " << app::name(from) << ": a change goes out at once, no change does not";
  }
}

TEST(KioskState, ADisplayThatGoesAwayShowsNoDisplayFromEveryState) {
  expect_transitions(
      "display lost", [](KioskState& k) { return k.display_lost(); }, [](State) { return State::no_display; });
}

TEST(KioskState, ClosingShowsClosedFromEveryState) {
  expect_transitions(
      "closed", [](KioskState& k) { return k.closed(); }, [](State) { return State::closed; });
}

TEST(KioskState, AFrameOfTheScenePlaysFromEveryState) {
  expect_transitions(
      "scene drawn", [](KioskState& k) { return k.frame_drawn(Shown::scene, false); }, [](State) { return State::playing; });
}

TEST(KioskState, AFrameOfTheSceneWithTheClockPausedIsPausedFromEveryState) {
  expect_transitions(
      "scene drawn paused", [](KioskState& k) { return k.frame_drawn(Shown::scene, true); }, [](State) { return State::paused; });
}

TEST(KioskState, AFrameWaitingForItsSceneIsLoadingFromEveryStatePausedOrNot) {
  for (bool paused : {false, true})
    expect_transitions(
        "loading drawn", [&](KioskState& k) { return k.frame_drawn(Shown::loading, paused); },
        [](State) { return State::loading; });
}

TEST(KioskState, AFrameWithNothingPlayableIsAnErrorFromEveryStatePausedOrNot) {
  for (bool paused : {false, true})
    expect_transitions(
        "nothing playable drawn", [&](KioskState& k) { return k.frame_drawn(Shown::nothing_playable, paused); },
        [](State) { return State::error; });
}

TEST(KioskState, StoppingReportsPlayingUnlessInErrorWithoutADisplayOrClosed) {
  expect_transitions(
      "stopped", [](KioskState& k) { return k.stopped(); },
      [](State from) {
        return from == State::error || from == State::no_display || from == State::closed ? from : State::playing;
      });
}

TEST(KioskState, PauseAndResumeAsTheButtonDoesThem) {
  KioskState kiosk = in(State::playing);
  EXPECT_TRUE(kiosk.frame_drawn(Shown::scene, true));
  EXPECT_EQ(kiosk.name(), "paused");
  EXPECT_FALSE(kiosk.frame_drawn(Shown::scene, true)) << "every frame of a pause is the same state";
  EXPECT_TRUE(kiosk.frame_drawn(Shown::scene, false));
  EXPECT_EQ(kiosk.name(), "playing");
}

TEST(KioskState, SkippingToAnItemNotLoadedYetShowsLoadingThenPlaying) {
  KioskState kiosk = in(State::playing);
  EXPECT_TRUE(kiosk.frame_drawn(Shown::loading, false));  // next, previous or restart onto a scene still uploading
  EXPECT_EQ(kiosk.state(), State::loading);
  EXPECT_TRUE(kiosk.frame_drawn(Shown::scene, false));
  EXPECT_EQ(kiosk.state(), State::playing);
}

TEST(KioskState, ADisplayThatComesBackLeavesNoDisplayWithItsFirstFrame) {
  KioskState kiosk = in(State::no_display);
  EXPECT_FALSE(kiosk.display_lost()) << "no display while none is there, checked every loop, is no change";
  EXPECT_TRUE(kiosk.frame_drawn(Shown::scene, false));
  EXPECT_EQ(kiosk.state(), State::playing);
}

TEST(KioskState, AFailedScheduleRecoversWhenAnItemPlaysAgain) {
  KioskState kiosk = in(State::error);
  EXPECT_TRUE(kiosk.frame_drawn(Shown::scene, false));  // a playlist reload with a good scene
  EXPECT_EQ(kiosk.state(), State::playing);
}

// ---- LED plans

struct Plan {
  State state;
  bool warning, check_failed;
  LedPattern status, error;
};

// board/README.md's table: the status LED tells the state, the error LED problems (a failed
// self-check fast, a warning slowly); in the error state the error LED is on and says nothing else.
constexpr Plan kPlans[] = {
    {State::starting, false, false, LedPattern::blink_fast, LedPattern::off},
    {State::starting, true, false, LedPattern::blink_fast, LedPattern::blink_slow},
    {State::starting, false, true, LedPattern::blink_fast, LedPattern::blink_fast},
    {State::starting, true, true, LedPattern::blink_fast, LedPattern::blink_fast},
    {State::loading, false, false, LedPattern::blink_slow, LedPattern::off},
    {State::loading, true, false, LedPattern::blink_slow, LedPattern::blink_slow},
    {State::loading, false, true, LedPattern::blink_slow, LedPattern::blink_fast},
    {State::loading, true, true, LedPattern::blink_slow, LedPattern::blink_fast},
    {State::playing, false, false, LedPattern::heartbeat, LedPattern::off},
    {State::playing, true, false, LedPattern::heartbeat, LedPattern::blink_slow},
    {State::playing, false, true, LedPattern::heartbeat, LedPattern::blink_fast},
    {State::playing, true, true, LedPattern::heartbeat, LedPattern::blink_fast},
    {State::paused, false, false, LedPattern::on, LedPattern::off},
    {State::paused, true, false, LedPattern::on, LedPattern::blink_slow},
    {State::paused, false, true, LedPattern::on, LedPattern::blink_fast},
    {State::paused, true, true, LedPattern::on, LedPattern::blink_fast},
    {State::error, false, false, LedPattern::off, LedPattern::on},
    {State::error, true, false, LedPattern::off, LedPattern::on},
    {State::error, false, true, LedPattern::off, LedPattern::on},
    {State::error, true, true, LedPattern::off, LedPattern::on},
    {State::no_display, false, false, LedPattern::blink_slow, LedPattern::off},
    {State::no_display, true, false, LedPattern::blink_slow, LedPattern::blink_slow},
    {State::no_display, false, true, LedPattern::blink_slow, LedPattern::blink_fast},
    {State::no_display, true, true, LedPattern::blink_slow, LedPattern::blink_fast},
    {State::closed, false, false, LedPattern::standby, LedPattern::off},
    {State::closed, true, false, LedPattern::standby, LedPattern::blink_slow},
    {State::closed, false, true, LedPattern::standby, LedPattern::blink_fast},
    {State::closed, true, true, LedPattern::standby, LedPattern::blink_fast},
};

TEST(KioskLeds, EveryStateWithAndWithoutWarningsAndAFailedCheck) {
  for (const Plan& p : kPlans) {
    const KioskState::LedPlan expected{p.status, p.error};
    EXPECT_EQ(app::led_plan(p.state, p.warning, p.check_failed), expected)
        << app::name(p.state) << " warning=" << p.warning << " check_failed=" << p.check_failed;
    // The same through the kiosk's own inputs: a lasting warning and a self-check's verdict.
    KioskState kiosk = in(p.state);
    kiosk.set_lasting_warning(p.warning);
    kiosk.check_finished(!p.check_failed);
    EXPECT_EQ(kiosk.leds(0.0), expected) << app::name(p.state);
  }
}

TEST(KioskLeds, AnErrorBlinksTheErrorLedSlowlyForAMinute) {
  KioskState kiosk = in(State::playing);
  EXPECT_EQ(kiosk.leds(100.0).error, LedPattern::off) << "no error yet";
  kiosk.error_reported(100.0);
  EXPECT_EQ(kiosk.leds(100.0).error, LedPattern::blink_slow);
  EXPECT_EQ(kiosk.leds(159.9).error, LedPattern::blink_slow);
  EXPECT_EQ(kiosk.leds(160.0).error, LedPattern::off);
  kiosk.error_reported(170.0);  // the same error again starts the minute again
  EXPECT_EQ(kiosk.leds(229.0).error, LedPattern::blink_slow);
  EXPECT_EQ(kiosk.leds(229.0).status, LedPattern::heartbeat) << "errors leave the status LED alone";
}

TEST(KioskLeds, AnErrorAtTimeZeroCountsToo) {
  KioskState kiosk;
  kiosk.error_reported(0.0);
  EXPECT_EQ(kiosk.leds(0.0).error, LedPattern::blink_slow);
}

TEST(KioskLeds, ALastingWarningBlinksUntilItClears) {
  KioskState kiosk = in(State::playing);
  kiosk.set_lasting_warning(true);  // the camera unplugged
  EXPECT_EQ(kiosk.leds(1e6).error, LedPattern::blink_slow) << "however long it lasts";
  kiosk.set_lasting_warning(false);  // plugged back
  EXPECT_EQ(kiosk.leds(1e6).error, LedPattern::off);
}

TEST(KioskLeds, AFailedSelfCheckBlinksFastUntilACheckPasses) {
  KioskState kiosk = in(State::playing);
  kiosk.check_finished(false);
  kiosk.set_lasting_warning(true);
  EXPECT_EQ(kiosk.leds(0.0).error, LedPattern::blink_fast) << "the failed check outranks a warning";
  kiosk.check_finished(true);
  EXPECT_EQ(kiosk.leds(0.0).error, LedPattern::blink_slow) << "the warning shows again";
}

TEST(KioskLeds, TheErrorStateLightsTheErrorLedWhateverElseHolds) {
  KioskState kiosk = in(State::error);
  kiosk.error_reported(0.0);
  kiosk.check_finished(false);
  EXPECT_EQ(kiosk.leds(0.0), (KioskState::LedPlan{LedPattern::off, LedPattern::on}));
}

}  // namespace
