#pragma once
// Opening hours: when a kiosk shows its playlist. Weekly ranges on the local time of one time zone,
// and holidays on which nothing opens. Outside them the player draws nothing and switches the display
// off, which is intended and no fault. Read from the board file's [schedule] (board/README.md).
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace date {
class time_zone;
}

namespace hal {

// One weekly range, "Mo-Fr 09:00-18:00": the days it opens on and its hours on each of them. A range
// whose end is not after its start runs past midnight ("Fr 20:00-02:00" closes on Saturday at 2).
struct OpeningRange {
  std::uint8_t days = 0;  // bit d: ISO weekday d + 1 (bit 0 Monday, bit 6 Sunday)
  int open_minute = 0;    // after the day's midnight
  int close_minute = 0;   // after open_minute; past 1440 on the next day
  bool operator==(const OpeningRange&) const = default;
};

// Parses one range: days (Mo Tu We Th Fr Sa Su, a span "Mo-Fr" that may wrap "Fr-Mo", or a list
// "Mo,We,Sa-Su"), a space, then HH:MM-HH:MM with 24:00 allowed as an end. "Mo-Su 00:00-24:00" is
// always open. False with what was expected in `error` ("hours as HH:MM-HH:MM ..., not '9-17'").
bool parse_opening_range(std::string_view text, OpeningRange& out, std::string& error);

class OpeningHours {
 public:
  using Time = std::chrono::sys_seconds;

  // `zone`: an IANA name such as "Europe/Budapest"; empty: the system's (/etc/localtime), or UTC
  // where it has none. False with why in `error` when the zone is unknown.
  static std::optional<OpeningHours> make(std::vector<OpeningRange> ranges, const std::string& zone,
                                          std::vector<std::chrono::year_month_day> holidays, std::string& error);

  bool open_at(Time t) const;
  // The first whole minute after `t` at which open_at() differs from open_at(t); none when it stays
  // the same for the next 400 days (every day a holiday, or a range open all week).
  std::optional<Time> next_change(Time t) const;
  // "2026-12-08 09:00 CET": a time as the schedule reads it, for the status file and the log.
  std::string local_text(Time t) const;
  const std::string& zone_name() const { return zone_name_; }

 private:
  OpeningHours() = default;
  // Open at `minute` of the local day `day` (days since 1970-01-01), by the ranges that start on that
  // day or ran over from the day before.
  bool open_on(long long day, int minute) const;
  bool holiday(long long day) const;

  const date::time_zone* zone_ = nullptr;
  std::string zone_name_;
  std::vector<OpeningRange> ranges_;
  std::vector<long long> holidays_;  // local days since 1970-01-01, sorted
};

}  // namespace hal
