#include "hal/opening_hours.h"

#include <date/tz.h>

#include <algorithm>
#include <array>
#include <charconv>

namespace hal {
namespace {

constexpr int kMinutesPerDay = 24 * 60;
// A schedule that does not change within this many days never will: the year's holidays repeat no
// further, and a week of ranges repeats every week.
constexpr long long kLookAheadDays = 400;
constexpr std::array<std::string_view, 7> kDayNames = {"Mo", "Tu", "We", "Th", "Fr", "Sa", "Su"};

// Monday 0 .. Sunday 6 of the day `day` days after 1970-01-01, a Thursday.
int weekday_index(long long day) {
  return static_cast<int>(((day + 3) % 7 + 7) % 7);
}

int day_index(std::string_view name) {
  const auto it = std::find(kDayNames.begin(), kDayNames.end(), name);
  return it == kDayNames.end() ? -1 : static_cast<int>(it - kDayNames.begin());
}

// "HH:MM" with HH 0..24 and MM 0..59, 24 only as 24:00; -1 when it is not one.
int minute_of(std::string_view text) {
  if (text.size() != 5 || text[2] != ':') return -1;
  int hours = 0, minutes = 0;
  const char* begin = text.data();
  if (std::from_chars(begin, begin + 2, hours).ptr != begin + 2 ||
      std::from_chars(begin + 3, begin + 5, minutes).ptr != begin + 5)
    return -1;
  if (hours > 24 || minutes > 59 || (hours == 24 && minutes != 0)) return -1;
  return hours * 60 + minutes;
}

using LocalMinutes = date::local_time<std::chrono::minutes>;

}  // namespace

bool parse_opening_range(std::string_view text, OpeningRange& out, std::string& error) {
  const size_t space = text.find(' ');
  if (space == std::string_view::npos || text.find(' ', space + 1) != std::string_view::npos) {
    error = "days and hours such as \"Mo-Fr 09:00-18:00\" or \"Sa,Su 10:00-16:00\"";
    return false;
  }
  OpeningRange range;
  std::string_view days = text.substr(0, space);
  while (!days.empty()) {
    const size_t comma = days.find(',');
    const std::string_view item = days.substr(0, comma);
    days = comma == std::string_view::npos ? std::string_view() : days.substr(comma + 1);
    const size_t dash = item.find('-');
    const int first = day_index(item.substr(0, dash));
    const int last = dash == std::string_view::npos ? first : day_index(item.substr(dash + 1));
    if (first < 0 || last < 0 || (comma != std::string_view::npos && days.empty())) {
      error = "days as Mo Tu We Th Fr Sa Su, a span (Mo-Fr) or a list (Mo,We,Sa-Su) before the hours, not '" + std::string(item) +
              "'";
      return false;
    }
    for (int d = first;; d = (d + 1) % 7) {  // a span that wraps, Fr-Mo, runs through the weekend
      range.days = static_cast<std::uint8_t>(range.days | (1u << d));
      if (d == last) break;
    }
  }
  const std::string_view hours = text.substr(space + 1);
  const size_t dash = hours.find('-');
  const int open = dash == std::string_view::npos ? -1 : minute_of(hours.substr(0, dash));
  const int close = dash == std::string_view::npos ? -1 : minute_of(hours.substr(dash + 1));
  if (open < 0 || close < 0 || open == kMinutesPerDay) {
    error = "hours as HH:MM-HH:MM (00:00 to 24:00) after the days, not '" + std::string(hours) + "'";
    return false;
  }
  range.open_minute = open;
  // An end at or before the start is on the next day: 20:00-02:00, or 09:00-09:00 for a whole day.
  range.close_minute = close > open ? close : close + kMinutesPerDay;
  out = range;
  return true;
}

std::optional<OpeningHours> OpeningHours::make(std::vector<OpeningRange> ranges, const std::string& zone,
                                               std::vector<std::chrono::year_month_day> holidays, std::string& error) {
  OpeningHours hours;
  try {
    if (!zone.empty()) {
      hours.zone_ = date::locate_zone(zone);
    } else {
      try {
        hours.zone_ = date::current_zone();
      } catch (const std::exception&) {
        hours.zone_ = date::locate_zone("UTC");  // as the C library does without /etc/localtime
      }
    }
  } catch (const std::exception& e) {
    error = zone.empty() ? std::string("the system's time zone and UTC are both unknown (is tzdata installed?): ") + e.what()
                         : "an IANA time zone such as \"Europe/Budapest\" (none is called '" + zone + "')";
    return std::nullopt;
  }
  hours.zone_name_ = std::string(hours.zone_->name());
  hours.ranges_ = std::move(ranges);
  for (const std::chrono::year_month_day& day : holidays)
    hours.holidays_.push_back(std::chrono::sys_days(day).time_since_epoch().count());
  std::sort(hours.holidays_.begin(), hours.holidays_.end());
  return hours;
}

bool OpeningHours::holiday(long long day) const {
  return std::binary_search(holidays_.begin(), holidays_.end(), day);
}

bool OpeningHours::open_on(long long day, int minute) const {
  const int today = weekday_index(day), yesterday = weekday_index(day - 1);
  for (const OpeningRange& r : ranges_) {
    if ((r.days >> today & 1u) != 0 && minute >= r.open_minute && minute < r.close_minute && !holiday(day)) return true;
    // What a range of yesterday's runs past midnight belongs to yesterday: a holiday today leaves it be.
    if ((r.days >> yesterday & 1u) != 0 && minute < r.close_minute - kMinutesPerDay && !holiday(day - 1)) return true;
  }
  return false;
}

bool OpeningHours::open_at(Time t) const {
  const auto local = std::chrono::floor<std::chrono::minutes>(zone_->to_local(t));
  const auto day = std::chrono::floor<date::days>(local);
  return open_on(day.time_since_epoch().count(), static_cast<int>((local - day).count()));
}

std::optional<OpeningHours::Time> OpeningHours::next_change(Time t) const {
  const bool open_now = open_at(t);
  const long long today = std::chrono::floor<date::days>(zone_->to_local(t)).time_since_epoch().count();
  std::optional<Time> first;
  // A state changes only where a range opens or closes. Day d's ranges open and close within
  // [d, d + 2) local days, so once a change is found, the day after is the last that can hold an
  // earlier one.
  for (long long day = today - 1; day <= today + kLookAheadDays; ++day) {
    if (first && LocalMinutes(std::chrono::minutes((day - 1) * kMinutesPerDay)) > zone_->to_local(*first)) break;
    for (const OpeningRange& r : ranges_)
      for (const int minute : {r.open_minute, r.close_minute}) {
        // A boundary in a daylight-saving gap (02:30 on the spring night) falls at the gap's end.
        const LocalMinutes local(std::chrono::minutes(day * kMinutesPerDay + minute));
        const Time boundary = std::chrono::floor<std::chrono::seconds>(zone_->to_sys(local, date::choose::earliest));
        if (boundary > t && (!first || boundary < *first) && open_at(boundary) != open_now) first = boundary;
      }
  }
  return first;
}

std::string OpeningHours::local_text(Time t) const {
  return date::format("%Y-%m-%d %H:%M %Z", date::make_zoned(zone_, t));
}

}  // namespace hal
