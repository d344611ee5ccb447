#include "play/status_reporter.h"

#include "base/cache_file.h"
#include "play/play_clock.h"

#include <unistd.h>

#include <algorithm>
#include <ostream>

namespace app {

void FrameStats::add(double ms) {
  window_[next_++ % window_.size()] = ms;
  count_ = std::min(count_ + 1, window_.size());
}

double FrameStats::percentile(double p) const {
  if (count_ == 0) return 0.0;
  std::array<double, 256> sorted{};
  std::copy_n(window_.begin(), count_, sorted.begin());
  std::sort(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(count_));
  return sorted[std::min(count_ - 1, static_cast<size_t>(p * static_cast<double>(count_)))];
}

namespace {

// Resident memory in KiB, from /proc/self/statm (only read when logging).
long resident_kib() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

}  // namespace

StatusReporter::StatusReporter(hal::Status& board, KioskState& kiosk, const PlayClock& clock, std::ostream& err)
    : board_(board),
      kiosk_(kiosk),
      clock_(clock),
      err_(err),
      status_led_(board.find_led("status")),
      error_led_(board.find_led("error")) {}

void StatusReporter::report(ErrorKind kind, const std::string& error) {
  ++metrics_.errors[static_cast<std::size_t>(kind)];
  err_ << "warning: " << error << "\n";
  kiosk_.error_reported(clock_.now());
  if (std::find(errors_.begin(), errors_.end(), error) != errors_.end()) return;
  errors_.push_back(error);
  constexpr size_t kKeep = 16;  // the recent ones; the oldest go first
  if (errors_.size() > kKeep) errors_.erase(errors_.begin());
}

void StatusReporter::note(const std::string& text) {
  if (!notes_.insert(text).second) return;
  err_ << "note: " << text << "\n";
}

bool StatusReporter::due(bool force) {
  const double now = clock_.now();
  constexpr double kPeriod = 2.0;  // often enough for a monitor, rarely enough for an SD card
  if (!force && now - last_status_s_ < kPeriod) return false;
  last_status_s_ = now;
  return true;
}

void StatusReporter::set_leds(bool lasting_warning) {
  kiosk_.set_lasting_warning(lasting_warning);
  const KioskState::LedPlan plan = kiosk_.leds(clock_.now());
  if (status_led_ && board_.pattern(*status_led_) != plan.status) board_.set_pattern(*status_led_, plan.status);
  if (error_led_ && board_.pattern(*error_led_) != plan.error) board_.set_pattern(*error_led_, plan.error);
}

void StatusReporter::open_metrics(const std::string& path, const Metrics& base) {
  metrics_path_ = path;
  metrics_.version = base.version;
  metrics_.platform = base.platform;
  metrics_.renderer = base.renderer;
  metrics_.start_unix_s = base.start_unix_s;
}

void StatusReporter::publish(hal::StatusReport report, int item) {
  // Every warning in the file is one that lasts, so the LEDs warn exactly when the file lists one.
  set_leds(!report.warnings.empty());
  report.state = std::string(kiosk_.name());
  report.frame_ms_p50 = stats_.percentile(0.5);
  report.frame_ms_p99 = stats_.percentile(0.99);
  report.fps = report.frame_ms_p50 > 0.0 ? 1000.0 / report.frame_ms_p50 : 0.0;
  report.errors = errors_;
  std::string error;
  if (!board_.write_report(report, &error) && error != last_status_error_) {
    last_status_error_ = error;
    err_ << "warning: " << error << "\n";
  }
  if (metrics_path_.empty()) return;
  static_assert(kStates.size() == static_cast<std::size_t>(KioskState::State::closed) + 1, "a name for every state");
  metrics_.state = kStates[static_cast<std::size_t>(kiosk_.state())];
  metrics_.item = item;
  metrics_.scene = report.item;
  metrics_.frames = report.frames;
  metrics_.frame_seconds_p50 = report.frame_ms_p50 / 1000.0;
  metrics_.frame_seconds_p99 = report.frame_ms_p99 / 1000.0;
  metrics_.resident_bytes = static_cast<std::uint64_t>(resident_kib()) * 1024u;
  if (report.self_check) {
    // The verdict's time is on the devices' clock; its age on that clock dates it in Unix time.
    const double age_s = std::chrono::duration<double>(clock_.devices().now() - report.self_check->time).count();
    metrics_.self_check = Metrics::Check{report.self_check->passed, report.self_check->score, wall_seconds() - age_s};
  }
  // Written whole beside and renamed over, as node_exporter's textfile collector asks.
  if (!base::write_file_whole(metrics_path_, format_metrics(metrics_), error)) {
    if (error != last_metrics_error_) err_ << "warning: metrics: " << error << "\n";
    last_metrics_error_ = error;
  } else {
    last_metrics_error_.clear();
  }
}

void StatusReporter::open_log(const std::string& path, bool append) {
  if (!path.empty()) log_.open(path, append ? std::ios::app : std::ios::trunc);
}

void StatusReporter::note_action(hal::Action action) {
  note_action(hal::to_string(action));
}

void StatusReporter::note_action(std::string_view name) {
  if (!pending_actions_.empty()) pending_actions_ += ",";
  pending_actions_ += name;
}

void StatusReporter::frame_presented(const FrameLogLine& line) {
  if (log_.is_open()) {
    log_ << line.frame << " t=" << line.now << " item=" << line.item << " state=" << kiosk_.name();
    for (size_t led = 0; led < board_.led_count(); ++led)
      log_ << ' ' << board_.led_name(led) << '=' << hal::to_string(board_.pattern(led));
    const PlayClock::Steady::time_point logged = PlayClock::Steady::now();
    log_ << " actions=" << (pending_actions_.empty() ? "-" : pending_actions_) << " camera=" << (line.camera_lost ? "lost" : "ok")
         << " swaps=" << line.swaps << " ms=" << std::chrono::duration<double, std::milli>(logged - last_log_).count()
         << " rss_kib=" << resident_kib() << "\n"
         << std::flush;  // read while the player runs (tests, benchmarks)
    last_log_ = logged;
  }
  pending_actions_.clear();
  const double frame_s = clock_.now();
  if (last_frame_s_ >= 0.0) {
    stats_.add((frame_s - last_frame_s_) * 1000.0);
    metrics_.frame_seconds_sum += frame_s - last_frame_s_;
    ++metrics_.frame_intervals;
  }
  last_frame_s_ = frame_s;
}

}  // namespace app
