// Whether the display is on, as a kiosk's operator sees it: the opening hours decide, a `player ctl
// display on|off` holds until the hours next change, and a clock set back by NTP is followed.
#include "play/opening_schedule.h"

#include <gtest/gtest.h>

#include <chrono>

namespace {

using app::OpeningSchedule;

// Monday 2026-12-07 at hh:mm UTC, in Unix seconds (the player's wall time).
double monday(int hh, int mm = 0, int days_later = 0) {
  return 1796601600.0 + days_later * 86400.0 + hh * 3600.0 + mm * 60.0;
}

hal::OpeningHours weekdays_nine_to_six() {
  hal::OpeningRange range;
  std::string error;
  EXPECT_TRUE(hal::parse_opening_range("Mo-Fr 09:00-18:00", range, error)) << error;
  std::optional<hal::OpeningHours> hours = hal::OpeningHours::make({range}, "UTC", {}, error);
  EXPECT_TRUE(hours) << error;
  return *hours;
}

TEST(OpeningSchedule, WithoutHoursTheDisplayIsOnUntilACommandSaysOtherwise) {
  OpeningSchedule schedule(nullptr);
  EXPECT_TRUE(schedule.update(monday(3), 0.0)) << "the first look is a change: the loop sets the display up from it";
  EXPECT_TRUE(schedule.on());
  EXPECT_FALSE(schedule.update(monday(4), 3600.0));
  EXPECT_EQ(schedule.describe(), "open");
  EXPECT_EQ(schedule.command(false), "ok: display off (no opening hours: until the next display command)");
  EXPECT_TRUE(schedule.update(monday(4), 3600.5));
  EXPECT_FALSE(schedule.on());
  EXPECT_FALSE(schedule.update(monday(4, 0, 30), 30 * 86400.0)) << "no hours change it back";
  EXPECT_EQ(schedule.describe(), "off by command");
  schedule.command(true);
  EXPECT_TRUE(schedule.update(monday(5, 0, 30), 30 * 86400.0 + 3600.0));
  EXPECT_TRUE(schedule.on());
}

TEST(OpeningSchedule, TheHoursSwitchTheDisplayAtTheirBoundaries) {
  const hal::OpeningHours hours = weekdays_nine_to_six();
  OpeningSchedule schedule(&hours);
  EXPECT_TRUE(schedule.update(monday(8, 59), 0.0));
  EXPECT_FALSE(schedule.on());
  EXPECT_EQ(schedule.describe(), "closed until 2026-12-07 09:00 UTC");
  EXPECT_TRUE(schedule.update(monday(9), 60.0)) << "at the boundary, not at the next minute's look";
  EXPECT_TRUE(schedule.on());
  EXPECT_EQ(schedule.describe(), "open until 2026-12-07 18:00 UTC");
  EXPECT_FALSE(schedule.update(monday(12), 3 * 3600.0));
  EXPECT_TRUE(schedule.update(monday(18), 9 * 3600.0));
  EXPECT_FALSE(schedule.on());
  EXPECT_EQ(schedule.describe(), "closed until 2026-12-08 09:00 UTC");
}

TEST(OpeningSchedule, ACommandHoldsUntilTheHoursNextChange) {
  const hal::OpeningHours hours = weekdays_nine_to_six();
  OpeningSchedule schedule(&hours);
  schedule.update(monday(10), 0.0);
  ASSERT_TRUE(schedule.on());
  EXPECT_EQ(schedule.command(true), "ok: display on (as the opening hours have it)");
  EXPECT_EQ(schedule.command(false), "ok: display off until the opening hours change at 2026-12-07 18:00 UTC");
  EXPECT_TRUE(schedule.update(monday(10, 1), 60.0));
  EXPECT_FALSE(schedule.on());
  EXPECT_EQ(schedule.describe(), "off by command until 2026-12-07 18:00 UTC");
  EXPECT_FALSE(schedule.update(monday(18), 8 * 3600.0)) << "closing leaves it off: no change to report";
  EXPECT_EQ(schedule.describe(), "closed until 2026-12-08 09:00 UTC") << "the command held until the hours changed";
  EXPECT_TRUE(schedule.update(monday(9, 0, 1), 23 * 3600.0));
  EXPECT_TRUE(schedule.on()) << "the next morning opens as the hours say";

  // On at night, for a visit after hours: until the next opening, which then goes on as usual.
  EXPECT_TRUE(schedule.update(monday(18, 0, 1), 32 * 3600.0));
  EXPECT_EQ(schedule.command(true), "ok: display on until the opening hours change at 2026-12-09 09:00 UTC");
  EXPECT_TRUE(schedule.update(monday(20, 0, 1), 34 * 3600.0));
  EXPECT_TRUE(schedule.on());
  EXPECT_FALSE(schedule.update(monday(9, 0, 2), 47 * 3600.0));
  EXPECT_EQ(schedule.describe(), "open until 2026-12-09 18:00 UTC");
  EXPECT_TRUE(schedule.update(monday(18, 0, 2), 56 * 3600.0));
  EXPECT_FALSE(schedule.on());
}

// A board without a clock boots in the past and NTP sets it later: the hours are looked at again a
// minute (monotonic) after the last look, whatever the wall clock did.
TEST(OpeningSchedule, AWallClockSetBackIsFollowedWithinAMinute) {
  const hal::OpeningHours hours = weekdays_nine_to_six();
  OpeningSchedule schedule(&hours);
  EXPECT_TRUE(schedule.update(monday(9, 0, 5), 0.0)) << "Saturday";
  EXPECT_FALSE(schedule.on());
  EXPECT_FALSE(schedule.update(monday(10), 30.0)) << "set back to Monday: seen at the next look, not yet";
  EXPECT_TRUE(schedule.update(monday(10, 1), 60.0));
  EXPECT_TRUE(schedule.on());
}

}  // namespace
