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

constexpr std::array<State, 6> kStates = {State::starting, State::loading, State::playing,
                                          State::paused,   State::error,   State::no_display};

// A kiosk in `state`, reached the way the player reaches it.
KioskState in(State state) {
  KioskState kiosk;
  switch (state) {
    case State::starting: break;
    case State::loading: kiosk.frame_drawn(Shown::loading, false); break;
    case State::playing: kiosk.frame_drawn(Shown::scene, false); break;
    case State::paused: kiosk.frame_drawn(Shown::scene, true); break;
    case State::error: kiosk.frame_drawn(Shown::nothing_playable, false); break;
    case State::no_display: kiosk.display_lost(); break;
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
  expect_transitions("display lost", [](KioskState& k) { return k.display_lost(); }, [](State) { return State::no_display; });
}

TEST(KioskState, AFrameOfTheScenePlaysFromEveryState) {
  expect_transitions("scene drawn", [](KioskState& k) { return k.frame_drawn(Shown::scene, false); },
                     [](State) { return State::playing; });
}

TEST(KioskState, AFrameOfTheSceneWithTheClockPausedIsPausedFromEveryState) {
  expect_transitions("scene drawn paused", [](KioskState& k) { return k.frame_drawn(Shown::scene, true); },
                     [](State) { return State::paused; });
}

TEST(KioskState, AFrameWaitingForItsSceneIsLoadingFromEveryStatePausedOrNot) {
  for (bool paused : {false, true})
    expect_transitions("loading drawn", [&](KioskState& k) { return k.frame_drawn(Shown::loading, paused); },
                       [](State) { return State::loading; });
}

TEST(KioskState, AFrameWithNothingPlayableIsAnErrorFromEveryStatePausedOrNot) {
  for (bool paused : {false, true})
    expect_transitions("nothing playable drawn", [&](KioskState& k) { return k.frame_drawn(Shown::nothing_playable, paused); },
                       [](State) { return State::error; });
}

TEST(KioskState, StoppingReportsPlayingUnlessInErrorOrWithoutADisplay) {
  expect_transitions("stopped", [](KioskState& k) { return k.stopped(); },
                     [](State from) { return from == State::error || from == State::no_display ? from : State::playing; });
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
    {State::starting, false, false, LedPattern::BlinkFast, LedPattern::Off},
    {State::starting, true, false, LedPattern::BlinkFast, LedPattern::BlinkSlow},
    {State::starting, false, true, LedPattern::BlinkFast, LedPattern::BlinkFast},
    {State::starting, true, true, LedPattern::BlinkFast, LedPattern::BlinkFast},
    {State::loading, false, false, LedPattern::BlinkSlow, LedPattern::Off},
    {State::loading, true, false, LedPattern::BlinkSlow, LedPattern::BlinkSlow},
    {State::loading, false, true, LedPattern::BlinkSlow, LedPattern::BlinkFast},
    {State::loading, true, true, LedPattern::BlinkSlow, LedPattern::BlinkFast},
    {State::playing, false, false, LedPattern::Heartbeat, LedPattern::Off},
    {State::playing, true, false, LedPattern::Heartbeat, LedPattern::BlinkSlow},
    {State::playing, false, true, LedPattern::Heartbeat, LedPattern::BlinkFast},
    {State::playing, true, true, LedPattern::Heartbeat, LedPattern::BlinkFast},
    {State::paused, false, false, LedPattern::On, LedPattern::Off},
    {State::paused, true, false, LedPattern::On, LedPattern::BlinkSlow},
    {State::paused, false, true, LedPattern::On, LedPattern::BlinkFast},
    {State::paused, true, true, LedPattern::On, LedPattern::BlinkFast},
    {State::error, false, false, LedPattern::Off, LedPattern::On},
    {State::error, true, false, LedPattern::Off, LedPattern::On},
    {State::error, false, true, LedPattern::Off, LedPattern::On},
    {State::error, true, true, LedPattern::Off, LedPattern::On},
    {State::no_display, false, false, LedPattern::BlinkSlow, LedPattern::Off},
    {State::no_display, true, false, LedPattern::BlinkSlow, LedPattern::BlinkSlow},
    {State::no_display, false, true, LedPattern::BlinkSlow, LedPattern::BlinkFast},
    {State::no_display, true, true, LedPattern::BlinkSlow, LedPattern::BlinkFast},
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
  EXPECT_EQ(kiosk.leds(100.0).error, LedPattern::Off) << "no error yet";
  kiosk.error_reported(100.0);
  EXPECT_EQ(kiosk.leds(100.0).error, LedPattern::BlinkSlow);
  EXPECT_EQ(kiosk.leds(159.9).error, LedPattern::BlinkSlow);
  EXPECT_EQ(kiosk.leds(160.0).error, LedPattern::Off);
  kiosk.error_reported(170.0);  // the same error again starts the minute again
  EXPECT_EQ(kiosk.leds(229.0).error, LedPattern::BlinkSlow);
  EXPECT_EQ(kiosk.leds(229.0).status, LedPattern::Heartbeat) << "errors leave the status LED alone";
}

TEST(KioskLeds, AnErrorAtTimeZeroCountsToo) {
  KioskState kiosk;
  kiosk.error_reported(0.0);
  EXPECT_EQ(kiosk.leds(0.0).error, LedPattern::BlinkSlow);
}

TEST(KioskLeds, ALastingWarningBlinksUntilItClears) {
  KioskState kiosk = in(State::playing);
  kiosk.set_lasting_warning(true);  // the camera unplugged
  EXPECT_EQ(kiosk.leds(1e6).error, LedPattern::BlinkSlow) << "however long it lasts";
  kiosk.set_lasting_warning(false);  // plugged back
  EXPECT_EQ(kiosk.leds(1e6).error, LedPattern::Off);
}

TEST(KioskLeds, AFailedSelfCheckBlinksFastUntilACheckPasses) {
  KioskState kiosk = in(State::playing);
  kiosk.check_finished(false);
  kiosk.set_lasting_warning(true);
  EXPECT_EQ(kiosk.leds(0.0).error, LedPattern::BlinkFast) << "the failed check outranks a warning";
  kiosk.check_finished(true);
  EXPECT_EQ(kiosk.leds(0.0).error, LedPattern::BlinkSlow) << "the warning shows again";
}

TEST(KioskLeds, TheErrorStateLightsTheErrorLedWhateverElseHolds) {
  KioskState kiosk = in(State::error);
  kiosk.error_reported(0.0);
  kiosk.check_finished(false);
  EXPECT_EQ(kiosk.leds(0.0), (KioskState::LedPlan{LedPattern::Off, LedPattern::On}));
}

}  // namespace
