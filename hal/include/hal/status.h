#pragma once
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "base/unique_fd.h"
#include "hal/clock.h"

namespace hal {

// standby: a short flash every 3 s, as a switched-off television's LED shows it is there and asleep.
enum class LedPattern : std::uint8_t { off, on, blink_slow, blink_fast, heartbeat, standby };
std::string_view to_string(LedPattern p);
bool parse_led_pattern(std::string_view text, LedPattern& out);

// LED level of a pattern `elapsed` after it was set, and when that level next changes
// (Nanos::max() for the steady patterns). Pure, so timing is tested without a clock.
bool pattern_level(LedPattern p, Nanos elapsed);
Nanos pattern_next_change(LedPattern p, Nanos elapsed);
// How long one cycle of the pattern takes (Nanos::max() for the steady ones): how long a pattern
// must be shown for someone to see all of it.
Nanos pattern_period(LedPattern p);

// Where LED levels go: GPIO lines on a board, a recording in tests.
class LedSink {
 public:
  virtual ~LedSink() = default;
  virtual void set(std::size_t led, bool on) = 0;
  // The last failure to drive an LED while running, naming it; empty when none.
  virtual const std::string& last_error() const;
};

struct CheckSummary {
  bool passed = false;
  double score = 0.0;
  std::string reason;
  Nanos time{0};
};

// What the status file reports.
struct StatusReport {
  std::string state = "starting";
  std::string item;                               // what is on screen: the item's scene
  std::uint64_t frames = 0;                       // presented since start
  double fps = 0.0;                               // over the last second or so
  double frame_ms_p50 = 0.0, frame_ms_p99 = 0.0;  // frame-to-frame times over a recent window
  std::vector<std::string> errors;                // the recent ones, newest last, each naming its file or device
  std::vector<std::string> warnings;              // conditions that hold now (a camera lost); gone when they clear
  std::optional<CheckSummary> self_check;         // the last display self-check
};

// Named LEDs driven by patterns from a timerfd, and the status file.
class Status {
 public:
  // `led_names[i]` is driven through sink->set(i, ...). An empty status_file disables the file.
  Status(std::vector<std::string> led_names, std::unique_ptr<LedSink> sink, const Clock& clock, std::string status_file);
  ~Status();
  Status(const Status&) = delete;
  Status& operator=(const Status&) = delete;

  int fd() const;  // readable when some LED level is due to change; then call update()
  void update();   // applies due levels and re-arms the timer; never throws or allocates

  std::size_t led_count() const { return names_.size(); }
  std::optional<std::size_t> find_led(std::string_view name) const;
  const std::string& led_name(std::size_t led) const { return names_[led]; }
  void set_pattern(std::size_t led, LedPattern p);
  LedPattern pattern(std::size_t led) const { return leds_[led].pattern; }
  bool level(std::size_t led) const { return leds_[led].level; }  // lit now (as of the last update())
  // The sink's last failure to drive an LED (e.g. its chip was removed); empty when none.
  const std::string& led_error() const { return sink_->last_error(); }

  // Writes the report as JSON to a temporary file next to the status file, fsyncs it and renames it
  // over the old one, so readers see the old or the new file, never a torn one.
  // Returns false with "<file>: <reason>" in *error on failure.
  bool write_report(const StatusReport& report, std::string* error);
  const std::string& status_file() const { return file_; }

 private:
  struct Led {
    LedPattern pattern = LedPattern::off;
    Nanos since{0};
    bool level = false;
  };
  void arm_timer();

  std::vector<std::string> names_;
  std::vector<Led> leds_;
  std::unique_ptr<LedSink> sink_;
  const Clock& clock_;
  std::string file_;
  base::UniqueFd timer_;
};

std::string report_to_json(const StatusReport& report);

}  // namespace hal
