// Opening hours: ranges as people write them, the time zone's local time across winter, summer and
// the spring gap, holidays, ranges past midnight, and the board file's [schedule] with its errors.
#include <gtest/gtest.h>

#include "hal/board.h"
#include "hal/opening_hours.h"

#include <chrono>

namespace hal {
namespace {

using namespace std::chrono;
using Time = OpeningHours::Time;

// A UTC time, as the tests write their expectations.
Time utc(int y, unsigned m, unsigned d, int hh, int mm) {
  return Time(sys_days(year_month_day(year(y), month(m), day(d))).time_since_epoch() + hours(hh) + minutes(mm));
}

OpeningRange range(const char* text) {
  OpeningRange r;
  std::string error;
  EXPECT_TRUE(parse_opening_range(text, r, error)) << text << ": " << error;
  return r;
}

std::string range_error(const char* text) {
  OpeningRange r;
  std::string error;
  EXPECT_FALSE(parse_opening_range(text, r, error)) << text;
  return error;
}

OpeningHours hours(std::vector<const char*> ranges, std::vector<year_month_day> holidays = {},
                   const std::string& zone = "Europe/Budapest") {
  std::vector<OpeningRange> parsed;
  for (const char* text : ranges) parsed.push_back(range(text));
  std::string error;
  std::optional<OpeningHours> made = OpeningHours::make(parsed, zone, holidays, error);
  EXPECT_TRUE(made) << error;
  return *made;
}

constexpr std::uint8_t kWeekdays = 0x1f, kWeekend = 0x60;

TEST(OpeningRange, DaysAndHoursAsPeopleWriteThem) {
  EXPECT_EQ(range("Mo-Fr 09:00-18:00"), (OpeningRange{kWeekdays, 9 * 60, 18 * 60}));
  EXPECT_EQ(range("Sa,Su 10:00-16:00"), (OpeningRange{kWeekend, 10 * 60, 16 * 60}));
  EXPECT_EQ(range("Mo,We,Sa-Su 10:00-16:00"), (OpeningRange{0x01 | 0x04 | kWeekend, 10 * 60, 16 * 60}));
  // A span that wraps runs through the weekend; hours that end before they start end the next day.
  EXPECT_EQ(range("Fr-Mo 20:00-02:00"), (OpeningRange{0x10 | kWeekend | 0x01, 20 * 60, 26 * 60}));
  EXPECT_EQ(range("Mo-Su 00:00-24:00"), (OpeningRange{0x7f, 0, 24 * 60}));
  EXPECT_EQ(range("Th 09:00-09:00"), (OpeningRange{0x08, 9 * 60, 33 * 60})) << "a whole day from 9 to 9";
  EXPECT_EQ(range("Su 23:59-00:00"), (OpeningRange{0x40, 23 * 60 + 59, 24 * 60}));
}

TEST(OpeningRange, WhatIsWrongIsSaid) {
  EXPECT_EQ(range_error("Mo-Fr"), "days and hours such as \"Mo-Fr 09:00-18:00\" or \"Sa,Su 10:00-16:00\"");
  EXPECT_EQ(range_error("Mo-Fr  09:00-18:00"), "days and hours such as \"Mo-Fr 09:00-18:00\" or \"Sa,Su 10:00-16:00\"");
  EXPECT_EQ(range_error("Mo-Fx 09:00-18:00"),
            "days as Mo Tu We Th Fr Sa Su, a span (Mo-Fr) or a list (Mo,We,Sa-Su) before the hours, not 'Mo-Fx'");
  EXPECT_EQ(range_error("mo 09:00-18:00"),
            "days as Mo Tu We Th Fr Sa Su, a span (Mo-Fr) or a list (Mo,We,Sa-Su) before the hours, not 'mo'");
  EXPECT_EQ(range_error("Mo, 09:00-18:00").substr(0, 8), "days as ");
  EXPECT_EQ(range_error("Mo 9-17"), "hours as HH:MM-HH:MM (00:00 to 24:00) after the days, not '9-17'");
  EXPECT_EQ(range_error("Mo 09:00"), "hours as HH:MM-HH:MM (00:00 to 24:00) after the days, not '09:00'");
  EXPECT_EQ(range_error("Mo 09:60-10:00").substr(0, 9), "hours as ");
  EXPECT_EQ(range_error("Mo 24:01-10:00").substr(0, 9), "hours as ");
  EXPECT_EQ(range_error("Mo 24:00-10:00").substr(0, 9), "hours as ") << "a range cannot open at the day's end";
  EXPECT_EQ(range_error("Mo 09:00-18:0x").substr(0, 9), "hours as ");
}

// Budapest keeps CET (UTC+1) in winter and CEST (UTC+2) in summer: 9 o'clock there is 8:00 UTC on
// Monday 2026-12-07 and 7:00 UTC on Monday 2026-07-06.
TEST(OpeningHours, OpenByTheZonesLocalTimeInWinterAndSummer) {
  const OpeningHours h = hours({"Mo-Fr 09:00-18:00", "Sa 10:00-16:00"});
  EXPECT_EQ(h.zone_name(), "Europe/Budapest");
  EXPECT_FALSE(h.open_at(utc(2026, 12, 7, 7, 59)));
  EXPECT_TRUE(h.open_at(utc(2026, 12, 7, 8, 0)));
  EXPECT_TRUE(h.open_at(utc(2026, 12, 7, 16, 59)));
  EXPECT_FALSE(h.open_at(utc(2026, 12, 7, 17, 0)));
  EXPECT_FALSE(h.open_at(utc(2026, 7, 6, 6, 59)));
  EXPECT_TRUE(h.open_at(utc(2026, 7, 6, 7, 0)));
  EXPECT_FALSE(h.open_at(utc(2026, 7, 6, 16, 0)));
  EXPECT_TRUE(h.open_at(utc(2026, 12, 12, 9, 0))) << "Saturday 10:00";
  EXPECT_FALSE(h.open_at(utc(2026, 12, 12, 15, 0))) << "Saturday 16:00";
  EXPECT_FALSE(h.open_at(utc(2026, 12, 13, 11, 0))) << "Sunday";
  EXPECT_EQ(h.local_text(utc(2026, 12, 7, 8, 0)), "2026-12-07 09:00 CET");
  EXPECT_EQ(h.local_text(utc(2026, 7, 6, 7, 0)), "2026-07-06 09:00 CEST");
}

TEST(OpeningHours, TheNextChangeIsTheNextOpeningOrClosing) {
  const OpeningHours h = hours({"Mo-Fr 09:00-18:00"});
  EXPECT_EQ(h.next_change(utc(2026, 12, 7, 11, 0)), utc(2026, 12, 7, 17, 0)) << "Monday noon: closes at 18:00";
  EXPECT_EQ(h.next_change(utc(2026, 12, 7, 17, 0)), utc(2026, 12, 8, 8, 0)) << "Monday 18:00: opens on Tuesday";
  EXPECT_EQ(h.next_change(utc(2026, 12, 11, 18, 0)), utc(2026, 12, 14, 8, 0)) << "Friday evening: opens on Monday";
  // Ranges that meet or overlap make one opening.
  const OpeningHours joined = hours({"Mo 09:00-12:00", "Mo 12:00-14:00", "Mo 13:00-18:00"});
  EXPECT_EQ(joined.next_change(utc(2026, 12, 7, 8, 0)), utc(2026, 12, 7, 17, 0));
  // Open all week, or a week of holidays only: nothing ever changes.
  EXPECT_FALSE(hours({"Mo-Su 00:00-24:00"}).next_change(utc(2026, 12, 7, 8, 0)));
  EXPECT_TRUE(hours({"Mo-Su 00:00-24:00"}).open_at(utc(2026, 12, 7, 8, 0)));
}

TEST(OpeningHours, AHolidayKeepsItsDayClosed) {
  const OpeningHours h = hours({"Mo-Fr 09:00-18:00"}, {year(2026) / December / 24, year(2026) / December / 25});
  EXPECT_TRUE(h.open_at(utc(2026, 12, 23, 12, 0)));
  EXPECT_FALSE(h.open_at(utc(2026, 12, 24, 12, 0)));
  EXPECT_FALSE(h.open_at(utc(2026, 12, 25, 12, 0)));
  EXPECT_EQ(h.next_change(utc(2026, 12, 23, 17, 0)), utc(2026, 12, 28, 8, 0)) << "Wednesday evening: opens on Monday";
}

// "Fr 20:00-02:00" is Friday's evening: it closes on Saturday at 2, Saturday a holiday or not, and a
// holiday on Friday cancels all of it.
TEST(OpeningHours, ARangePastMidnightBelongsToTheDayItStarts) {
  const OpeningHours h = hours({"Fr 20:00-02:00"});
  EXPECT_TRUE(h.open_at(utc(2026, 12, 11, 19, 0)));
  EXPECT_TRUE(h.open_at(utc(2026, 12, 12, 0, 59))) << "Saturday 01:59";
  EXPECT_FALSE(h.open_at(utc(2026, 12, 12, 1, 0))) << "Saturday 02:00";
  EXPECT_EQ(h.next_change(utc(2026, 12, 11, 20, 0)), utc(2026, 12, 12, 1, 0));
  const OpeningHours saturday_off = hours({"Fr 20:00-02:00"}, {year(2026) / December / 12});
  EXPECT_TRUE(saturday_off.open_at(utc(2026, 12, 12, 0, 0)));
  const OpeningHours friday_off = hours({"Fr 20:00-02:00"}, {year(2026) / December / 11});
  EXPECT_FALSE(friday_off.open_at(utc(2026, 12, 11, 20, 0)));
  EXPECT_FALSE(friday_off.open_at(utc(2026, 12, 12, 0, 0)));
  EXPECT_EQ(friday_off.next_change(utc(2026, 12, 11, 12, 0)), utc(2026, 12, 18, 19, 0)) << "the Friday after";
}

// On 2027-03-28 Budapest's clocks go from 02:00 CET to 03:00 CEST: a range that ends at 02:30 ends
// when the gap does, 01:00 UTC.
TEST(OpeningHours, ABoundaryInTheSpringGapFallsAtItsEnd) {
  const OpeningHours h = hours({"Su 01:00-02:30"});
  EXPECT_TRUE(h.open_at(utc(2027, 3, 28, 0, 30)));
  EXPECT_EQ(h.next_change(utc(2027, 3, 28, 0, 30)), utc(2027, 3, 28, 1, 0));
  EXPECT_FALSE(h.open_at(utc(2027, 3, 28, 1, 0)));
}

TEST(OpeningHours, AnUnknownZoneIsRefusedAndNoneMeansTheSystems) {
  std::string error;
  EXPECT_FALSE(OpeningHours::make({range("Mo 09:00-10:00")}, "Europe/Atlantis", {}, error));
  EXPECT_EQ(error, "an IANA time zone such as \"Europe/Budapest\" (none is called 'Europe/Atlantis')");
  const std::optional<OpeningHours> system = OpeningHours::make({range("Mo 09:00-10:00")}, "", {}, error);
  ASSERT_TRUE(system) << error;
  EXPECT_FALSE(system->zone_name().empty());
  const OpeningHours in_utc = hours({"Mo 09:00-10:00"}, {}, "UTC");
  EXPECT_TRUE(in_utc.open_at(utc(2026, 12, 7, 9, 0)));
  EXPECT_FALSE(in_utc.open_at(utc(2026, 12, 7, 10, 0)));
}

std::string board_error(const std::string& toml) {
  try {
    parse_board(toml, "b.toml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(OpeningHours, TheBoardFilesScheduleIsReadWithItsHolidays) {
  const BoardConfig b = parse_board(R"([schedule]
open = ["Mo-Fr 09:00-18:00", "Sa 10:00-16:00"]
timezone = "Europe/Budapest"
holidays = [2026-12-24, "2026-12-25"]
)",
                                    "b.toml");
  ASSERT_TRUE(b.schedule);
  EXPECT_EQ(b.schedule->zone_name(), "Europe/Budapest");
  EXPECT_TRUE(b.schedule->open_at(utc(2026, 12, 23, 12, 0)));
  EXPECT_FALSE(b.schedule->open_at(utc(2026, 12, 24, 12, 0)));
  EXPECT_FALSE(b.schedule->open_at(utc(2026, 12, 25, 12, 0)));
  EXPECT_TRUE(b.schedule->open_at(utc(2026, 12, 26, 12, 0))) << "Saturday";
  EXPECT_FALSE(parse_board("[board]\nname = \"x\"\n", "b.toml").schedule) << "no [schedule]: always open";
}

TEST(OpeningHours, TheBoardFilesScheduleErrorsNamePlaceFieldAndWhatWasExpected) {
  EXPECT_EQ(board_error("[schedule]\nopen = [\"Mo-Fr 09:00-18:00\", \"Sa 10-16\"]\n"),
            "b.toml:2:30: schedule.open[1]: expected hours as HH:MM-HH:MM (00:00 to 24:00) after the days, not '10-16', got 'Sa "
            "10-16'");
  EXPECT_EQ(board_error("[schedule]\nopen = [9]\n"),
            "b.toml:2:9: schedule.open[0]: expected a string such as \"Mo-Fr 09:00-18:00\", got 9");
  EXPECT_EQ(
      board_error("[schedule]\nopen = []\n"),
      "b.toml:2:8: schedule.open: expected a list of weekly ranges such as [\"Mo-Fr 09:00-18:00\", \"Sa 10:00-16:00\"], got "
      "array");
  EXPECT_EQ(
      board_error("[schedule]\ntimezone = \"UTC\"\n"),
      "b.toml:1:1: schedule.open: expected a list of weekly ranges such as [\"Mo-Fr 09:00-18:00\", \"Sa 10:00-16:00\"], got "
      "nothing");
  EXPECT_EQ(board_error("[schedule]\nopen = [\"Mo 09:00-10:00\"]\ntimezone = \"Mars/Olympus\"\n"),
            "b.toml:3:12: schedule.timezone: expected an IANA time zone such as \"Europe/Budapest\" (none is called "
            "'Mars/Olympus'), got 'Mars/Olympus'");
  EXPECT_EQ(board_error("[schedule]\nopen = [\"Mo 09:00-10:00\"]\nholidays = [\"2026-02-30\"]\n"),
            "b.toml:3:13: schedule.holidays[0]: expected a date that exists, as 2026-12-24 or \"2026-12-24\", got '2026-02-30'");
  EXPECT_EQ(board_error("[schedule]\nopen = [\"Mo 09:00-10:00\"]\nholidays = [\"24.12.2026\"]\n").substr(0, 35),
            "b.toml:3:13: schedule.holidays[0]: ");
  EXPECT_EQ(board_error("[schedule]\nopen = [\"Mo 09:00-10:00\"]\nclosed = [\"2026-12-24\"]\n"),
            "b.toml:3:10: schedule.closed: unknown key (expected one of open, timezone, holidays)");
}

}  // namespace
}  // namespace hal
