#include "hal/status.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <nlohmann/json.hpp>

#include "base/errno_text.h"
#include "base/names.h"
#include "fd.h"
#include "hal/mock.h"

namespace hal {

namespace {

using std::chrono::milliseconds;

constexpr base::Name<LedPattern> kLedPatternNames[] = {{LedPattern::off, "off"},
                                                       {LedPattern::on, "on"},
                                                       {LedPattern::blink_slow, "blink-slow"},
                                                       {LedPattern::blink_fast, "blink-fast"},
                                                       {LedPattern::heartbeat, "heartbeat"},
                                                       {LedPattern::standby, "standby"}};
static_assert(base::in_enum_order(kLedPatternNames));

// A pattern is a period and the phases within it where the level toggles, starting on.
struct PatternShape {
  Nanos period;
  std::array<Nanos, 4> toggles;
  std::size_t count;
};

PatternShape shape(LedPattern p) {
  switch (p) {
    case LedPattern::off:
    case LedPattern::on:
      return {Nanos::max(), {}, 0};
    case LedPattern::blink_slow:
      return {milliseconds(1000), {milliseconds(500)}, 1};
    case LedPattern::blink_fast:
      return {milliseconds(200), {milliseconds(100)}, 1};
    // Two short beats then a pause, the rhythm people read as "alive".
    case LedPattern::heartbeat:
      return {milliseconds(1200), {milliseconds(100), milliseconds(250), milliseconds(350)}, 3};
    case LedPattern::standby:
      return {milliseconds(3000), {milliseconds(100)}, 1};
  }
  return {Nanos::max(), {}, 0};
}

}  // namespace

std::string_view to_string(LedPattern p) {
  return base::name_of(kLedPatternNames, p);
}
bool parse_led_pattern(std::string_view text, LedPattern& out) {
  return base::parse_name(kLedPatternNames, text, out);
}

bool pattern_level(LedPattern p, Nanos elapsed) {
  if (p == LedPattern::off) return false;
  if (p == LedPattern::on) return true;
  const PatternShape s = shape(p);
  const Nanos phase = elapsed % s.period;
  std::size_t passed = 0;
  while (passed < s.count && s.toggles[passed] <= phase) ++passed;
  return passed % 2 == 0;
}

Nanos pattern_next_change(LedPattern p, Nanos elapsed) {
  if (p == LedPattern::off || p == LedPattern::on) return Nanos::max();
  const PatternShape s = shape(p);
  const Nanos phase = elapsed % s.period;
  const Nanos period_start = elapsed - phase;
  for (std::size_t i = 0; i < s.count; ++i)
    if (s.toggles[i] > phase) return period_start + s.toggles[i];
  return period_start + s.period;
}

Nanos pattern_period(LedPattern p) {
  return shape(p).period;
}

const std::string& LedSink::last_error() const {
  static const std::string none;
  return none;
}

void RecordingLedSink::set(std::size_t led, bool on) {
  if (levels_[led] == on) return;
  levels_[led] = on;
  changes->push_back({led, on, clock_.now()});
}

Status::Status(std::vector<std::string> led_names, std::unique_ptr<LedSink> sink, const Clock& clock, std::string status_file)
    : names_(std::move(led_names)),
      leds_(names_.size()),
      sink_(std::move(sink)),
      clock_(clock),
      file_(std::move(status_file)),
      timer_(detail::make_timer()) {
  for (std::size_t i = 0; i < leds_.size(); ++i) sink_->set(i, false);
}

Status::~Status() {
  for (std::size_t i = 0; i < leds_.size(); ++i) sink_->set(i, false);
}

int Status::fd() const {
  return timer_.get();
}

std::optional<std::size_t> Status::find_led(std::string_view name) const {
  for (std::size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == name) return i;
  return std::nullopt;
}

void Status::set_pattern(std::size_t led, LedPattern p) {
  leds_[led].pattern = p;
  leds_[led].since = clock_.now();
  update();
}

void Status::update() {
  detail::drain(timer_.get());
  const Nanos now = clock_.now();
  for (std::size_t i = 0; i < leds_.size(); ++i) {
    Led& led = leds_[i];
    const bool level = pattern_level(led.pattern, now - led.since);
    if (level != led.level) {
      led.level = level;
      sink_->set(i, level);
    }
  }
  arm_timer();
}

void Status::arm_timer() {
  const Nanos now = clock_.now();
  Nanos next = Nanos::max();
  for (const Led& led : leds_) {
    const Nanos change = pattern_next_change(led.pattern, now - led.since);
    if (change != Nanos::max()) next = std::min(next, led.since + change);
  }
  detail::arm_timer(timer_.get(), next);
}

std::string report_to_json(const StatusReport& report) {
  nlohmann::json j;
  j["state"] = report.state;
  j["item"] = report.item;
  j["frames"] = report.frames;
  j["fps"] = report.fps;
  j["frame_ms_p50"] = report.frame_ms_p50;
  j["frame_ms_p99"] = report.frame_ms_p99;
  j["errors"] = report.errors;
  j["warnings"] = report.warnings;
  if (report.self_check) {
    const auto& c = *report.self_check;
    j["self_check"] = {{"passed", c.passed},
                       {"score", c.score},
                       {"reason", c.reason},
                       {"monotonic_ms", std::chrono::duration_cast<milliseconds>(c.time).count()}};
  } else {
    j["self_check"] = nullptr;
  }
  return j.dump(2) + "\n";
}

bool Status::write_report(const StatusReport& report, std::string* error) {
  if (file_.empty()) return true;
  auto fail = [&](const std::string& what, int err) {
    if (error) *error = file_ + ": " + what + ": " + base::errno_text(err);
    return false;
  };
  nlohmann::json j = nlohmann::json::parse(report_to_json(report));
  for (std::size_t i = 0; i < leds_.size(); ++i) j["leds"][names_[i]] = std::string(to_string(leds_[i].pattern));
  const std::string text = j.dump(2) + "\n";

  // The temporary lives in the same directory so rename() is atomic (same file system).
  std::string tmp = file_ + ".XXXXXX";
  base::UniqueFd fd(mkostemp(tmp.data(), O_CLOEXEC));
  if (!fd) return fail("cannot create temporary " + tmp, errno);
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd.get(), text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      const int err = errno;
      ::unlink(tmp.c_str());
      return fail("write " + tmp, err);
    }
    done += static_cast<std::size_t>(n);
  }
  // Readable by monitoring tools that run as another user.
  fchmod(fd.get(), 0644);
  if (fsync(fd.get()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    return fail("fsync " + tmp, err);
  }
  fd.reset();
  if (std::rename(tmp.c_str(), file_.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    return fail("rename " + tmp, err);
  }
  // fsync the directory too, or a power cut can lose the rename itself.
  const auto slash = file_.rfind('/');
  const std::string dir = slash == std::string::npos ? "." : (slash == 0 ? "/" : file_.substr(0, slash));
  if (base::UniqueFd dfd(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)); dfd) fsync(dfd.get());
  return true;
}

}  // namespace hal
