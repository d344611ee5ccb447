// Debounce, long press and auto-repeat, driven by a script and a manual clock.
#include <gtest/gtest.h>

#include <array>
#include <fstream>
#include <sstream>
#include <vector>

#include "button_logic.h"
#include "hal/board.h"
#include "hal/mock.h"

namespace hal {
namespace {

using std::chrono::milliseconds;

struct Rec {
  std::string button;
  ButtonAction action;
  long long ms;
  bool operator==(const Rec&) const = default;
};
std::ostream& operator<<(std::ostream& os, const Rec& r) {
  return os << r.button << " " << to_string(r.action) << " @" << r.ms;
}

// Steps the clock 1 ms at a time, as a poll loop would wake, collecting every event.
std::vector<Rec> run(MockButtons& b, ManualClock& clock, long long until_ms) {
  std::vector<Rec> out;
  std::array<ButtonEvent, 4> ev;
  while (clock.now() < milliseconds(until_ms)) {
    clock.advance(milliseconds(1));
    for (std::size_t n; (n = b.read(ev)) > 0;)
      for (std::size_t i = 0; i < n; ++i)
        out.push_back(
            {std::string(b.name(ev[i].button)), ev[i].action, std::chrono::duration_cast<milliseconds>(ev[i].time).count()});
  }
  return out;
}

ButtonTiming timing(int debounce, int long_press, int repeat_delay = 0, int repeat_interval = 100) {
  return {milliseconds(debounce), milliseconds(long_press), milliseconds(repeat_delay), milliseconds(repeat_interval)};
}

TEST(Buttons, BounceIsFilteredAndTimestampIsWhenTheLevelSettled) {
  ManualClock clock;
  MockButtons b({{"play", timing(20, 0)}},
                parse_button_script("100 play press\n103 play release\n106 play press\n"
                                    "300 play release\n305 play press\n309 play release\n",
                                    "bounce"),
                clock);
  const auto events = run(b, clock, 500);
  EXPECT_EQ(events, (std::vector<Rec>{{"play", ButtonAction::press, 106}, {"play", ButtonAction::release, 309}}));
}

TEST(Buttons, PulseShorterThanDebounceIsIgnored) {
  ManualClock clock;
  MockButtons b({{"play", timing(20, 0)}}, parse_button_script("100 play press\n110 play release\n", "glitch"), clock);
  EXPECT_TRUE(run(b, clock, 300).empty());
}

TEST(Buttons, EventIsNotReportedBeforeTheDebounceTimeHasPassed) {
  ManualClock clock;
  MockButtons b({{"play", timing(20, 0)}}, parse_button_script("100 play press\n", "s"), clock);
  EXPECT_TRUE(run(b, clock, 119).empty());
  EXPECT_EQ(run(b, clock, 121), (std::vector<Rec>{{"play", ButtonAction::press, 100}}));
}

TEST(Buttons, LongPressFiresOnceAtItsDeadlineWhileHeld) {
  ManualClock clock;
  MockButtons b({{"check", timing(10, 800)}},
                parse_button_script("100 check press\n1500 check release\n2000 check press\n2300 check release\n", "s"), clock);
  EXPECT_EQ(run(b, clock, 2600), (std::vector<Rec>{{"check", ButtonAction::press, 100},
                                                   {"check", ButtonAction::long_press, 900},
                                                   {"check", ButtonAction::release, 1500},
                                                   {"check", ButtonAction::press, 2000},
                                                   {"check", ButtonAction::release, 2300}}));
}

// A button already held down when the player starts (the line reads pressed at start-up) is not a
// press: however long it stays down, no press, long press or repeat. Let go, its release is reported
// (whoever tracks held buttons sees it up), and its next press is an ordinary one, long press and
// repeats included.
TEST(Buttons, AButtonHeldWhenThePlayerStartsDoesNothingUntilPressedAgain) {
  detail::ButtonLogic logic({timing(10, 800, 300, 200)});
  logic.set_initial(0, true);
  auto events_until = [&](long long ms) {
    logic.advance(milliseconds(ms));
    std::vector<std::pair<ButtonAction, long long>> out;
    std::array<ButtonEvent, 8> ev;
    for (std::size_t n; (n = logic.drain(ev)) > 0;)
      for (std::size_t i = 0; i < n; ++i)
        out.emplace_back(ev[i].action, std::chrono::duration_cast<milliseconds>(ev[i].time).count());
    return out;
  };
  EXPECT_TRUE(events_until(5000).empty());
  EXPECT_EQ(logic.next_deadline(), Nanos::max()) << "nothing is pending for the held button";
  logic.edge(0, false, milliseconds(6000));
  logic.edge(0, true, milliseconds(7000));
  using A = ButtonAction;
  EXPECT_EQ(
      events_until(7850),
      (std::vector<std::pair<ButtonAction, long long>>{
          {A::release, 6000}, {A::press, 7000}, {A::repeat, 7300}, {A::repeat, 7500}, {A::repeat, 7700}, {A::long_press, 7800}}));
}

TEST(Buttons, AutoRepeatStartsAfterDelayAndStopsOnRelease) {
  ManualClock clock;
  MockButtons b({{"next", timing(10, 0, 400, 100)}}, parse_button_script("0 next press\n650 next release\n", "s"), clock);
  EXPECT_EQ(run(b, clock, 1000), (std::vector<Rec>{{"next", ButtonAction::press, 0},
                                                   {"next", ButtonAction::repeat, 400},
                                                   {"next", ButtonAction::repeat, 500},
                                                   {"next", ButtonAction::repeat, 600},
                                                   {"next", ButtonAction::release, 650}}));
}

TEST(Buttons, LongPressAndAutoRepeatTogetherOnOneButton) {
  ManualClock clock;
  MockButtons b({{"next", timing(10, 800, 400, 100)}}, parse_button_script("0 next press\n1050 next release\n", "s"), clock);
  // Repeats keep their rhythm through the long press; at a tie the long press comes first.
  EXPECT_EQ(run(b, clock, 1300), (std::vector<Rec>{{"next", ButtonAction::press, 0},
                                                   {"next", ButtonAction::repeat, 400},
                                                   {"next", ButtonAction::repeat, 500},
                                                   {"next", ButtonAction::repeat, 600},
                                                   {"next", ButtonAction::repeat, 700},
                                                   {"next", ButtonAction::long_press, 800},
                                                   {"next", ButtonAction::repeat, 800},
                                                   {"next", ButtonAction::repeat, 900},
                                                   {"next", ButtonAction::repeat, 1000},
                                                   {"next", ButtonAction::release, 1050}}));
  EXPECT_EQ(b.dropped(), 0u);
}

// Reads everything queued in one go, as an app that stalled would.
std::vector<ButtonEvent> read_all(Buttons& b) {
  std::vector<ButtonEvent> all;
  std::array<ButtonEvent, 64> ev;
  for (std::size_t n; (n = b.read(ev)) > 0;) all.insert(all.end(), ev.begin(), ev.begin() + static_cast<long>(n));
  return all;
}

TEST(Buttons, FullQueueDropsRepeatsFirstKeepsPressLongPressAndRelease) {
  ManualClock clock;
  // Held 5 s with a repeat every 10 ms: about 500 events, far more than the queue holds.
  MockButtons b({{"next", timing(1, 800, 10, 10)}}, parse_button_script("0 next press\n5000 next release\n", "s"), clock);
  clock.set(milliseconds(6000));
  const std::vector<ButtonEvent> got = read_all(b);
  // At 10, 20, ... 5000: the release counts only once its 1 ms debounce has passed.
  const std::size_t repeats = (5000 - 10) / 10 + 1;
  const std::size_t produced = repeats + 3;  // press, long press, release
  ASSERT_EQ(got.size(), 256u);
  EXPECT_EQ(b.dropped(), produced - got.size());
  EXPECT_EQ(got.front().action, ButtonAction::press);
  EXPECT_EQ(got[1].action, ButtonAction::long_press);
  EXPECT_EQ(got.back().action, ButtonAction::release);
  EXPECT_EQ(got.back().time, milliseconds(5000));
  for (std::size_t i = 2; i + 1 < got.size(); ++i) EXPECT_EQ(got[i].action, ButtonAction::repeat) << i;
  // The oldest repeats went: the ones kept are the latest, still in time order.
  EXPECT_EQ(got[got.size() - 2].time, milliseconds(5000));
  EXPECT_EQ(got[2].time, milliseconds(5000 - 10 * 252));
  for (std::size_t i = 1; i < got.size(); ++i) EXPECT_LE(got[i - 1].time, got[i].time) << i;
}

TEST(Buttons, FullQueueNeverLeavesAButtonLookingHeld) {
  ManualClock clock;
  // 300 clicks of "a" while "b" is held: 601 events. Whole clicks go first; once only Releases of
  // "a" are left, one that another follows is dropped. The Press of the held "b" stays.
  std::string script = "0 b press\n";
  for (int i = 0; i < 300; ++i)
    script += std::to_string(10 + 10 * i) + " a press\n" + std::to_string(15 + 10 * i) + " a release\n";
  MockButtons b({{"a", timing(1, 0)}, {"b", timing(1, 0)}}, parse_button_script(script, "s"), clock);
  clock.set(milliseconds(10000));
  const std::vector<ButtonEvent> got = read_all(b);
  EXPECT_EQ(got.size() + b.dropped(), 601u);
  EXPECT_GT(b.dropped(), 0u);
  // Replaying what the app saw: "a" ends released, "b" (never released) ends held.
  std::array<bool, 2> held{};
  for (const ButtonEvent& e : got) {
    if (e.action == ButtonAction::press) held[e.button] = true;
    if (e.action == ButtonAction::release) held[e.button] = false;
  }
  EXPECT_FALSE(held[0]);
  EXPECT_TRUE(held[1]);
  EXPECT_EQ(got.front().button, 1);
  EXPECT_EQ(got.back().action, ButtonAction::release);
  EXPECT_EQ(got.back().time, milliseconds(15 + 10 * 299));
  for (std::size_t i = 1; i < got.size(); ++i) EXPECT_LE(got[i - 1].time, got[i].time) << i;
}

TEST(Buttons, EventsOfSeveralButtonsComeOutInTimeOrderEvenWhenReadLate) {
  ManualClock clock;
  MockButtons b({{"a", timing(5, 300)}, {"b", timing(5, 100)}},
                parse_button_script("0 a press\n50 b press\n400 a release\n400 b release\n", "s"), clock);
  clock.set(milliseconds(1000));  // the app was busy: everything is read in one go
  std::array<ButtonEvent, 16> ev;
  const std::size_t n = b.read(ev);
  ASSERT_EQ(n, 6u);
  for (std::size_t i = 1; i < n; ++i) EXPECT_LE(ev[i - 1].time, ev[i].time) << i;
  EXPECT_EQ(ev[1].action, ButtonAction::press);
  EXPECT_EQ(ev[1].button, 1);
  EXPECT_EQ(ev[2].action, ButtonAction::long_press);
  EXPECT_EQ(ev[2].time, milliseconds(150));
}

TEST(Buttons, InjectedKeysGoThroughTheSameDebounce) {
  ManualClock clock;
  MockButtons b({{"play", timing(20, 0)}}, {}, clock);
  clock.set(milliseconds(10));
  b.inject(0, true);
  EXPECT_TRUE(run(b, clock, 25).empty());
  EXPECT_EQ(run(b, clock, 40), (std::vector<Rec>{{"play", ButtonAction::press, 10}}));
}

TEST(Buttons, ScriptErrorsNameFileLineAndField) {
  auto message = [](const std::string& text) {
    try {
      parse_button_script(text, "buttons.script");
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("# ok\n100 play press\nabc play press\n"),
            "buttons.script:3: time: expected non-negative milliseconds, got 'abc'");
  EXPECT_EQ(message("100 play push\n"), "buttons.script:1: action: expected 'press' or 'release', got 'push'");
  EXPECT_EQ(message("100 a press\n50 a release\n"),
            "buttons.script:2: time: expected times that do not decrease, got 50 after 100");
  ManualClock clock;
  EXPECT_THROW(MockButtons({{"play", {}}}, parse_button_script("1 stop press\n", "s"), clock), ConfigError);
}

// Found by tests/fuzz (button_script): a time near long long's limit overflowed the conversion to
// nanoseconds (UB) instead of being refused.
TEST(Buttons, ScriptTimeBeyondWhatTheClockHoldsIsRefused) {
  const std::string path = std::string(HAL_SOURCE_DIR) + "/tests/fuzz/regressions/button_script/time_beyond_nanoseconds.script";
  std::ifstream in(path);
  ASSERT_TRUE(in) << path;
  std::stringstream text;
  text << in.rdbuf();
  try {
    parse_button_script(text.str(), "time_beyond_nanoseconds.script");
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(),
                 "time_beyond_nanoseconds.script:2: time: expected at most 3153600000000 milliseconds (100 years), "
                 "got 9223372036854775807");
  }
  EXPECT_EQ(parse_button_script("3153600000000 play press\n", "s").back().at, std::chrono::milliseconds(3153600000000));
}

}  // namespace
}  // namespace hal
