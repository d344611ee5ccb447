#pragma once
// What the board tells about the player, fed by KioskState: the status file (every two seconds, or
// at once on a change), the status and error LEDs, systemd's STATUS and watchdog (ServiceNotifier),
// the per-frame --log line, and the errors every piece reports.
#include "hal/board.h"
#include "hal/status.h"
#include "play/kiosk_state.h"
#include "play/metrics_file.h"
#include "play/play_clock.h"
#include "service_notify.h"

#include <array>
#include <chrono>
#include <cstdint>
#include <fstream>
#include <iosfwd>
#include <optional>
#include <string>
#include <unordered_set>
#include <vector>

namespace app {

// Frame-to-frame times over a window, for the status file.
class FrameStats {
 public:
  void add(double ms);
  double percentile(double p) const;

 private:
  std::array<double, 256> window_{};
  size_t next_ = 0, count_ = 0;
};

// One line of --log, read while the player runs (tests, benchmarks).
struct FrameLogLine {
  long long frame = 0;
  double now = 0.0;
  int item = -1;
  bool camera_lost = false;
  std::uint64_t swaps = 0;
};

class StatusReporter {
 public:
  StatusReporter(hal::Status& board, KioskState& kiosk, const PlayClock& clock, std::ostream& err);

  // An error: "warning: ..." on stderr, kept in the status file's errors (the recent 16, each once),
  // and the error LED's warning for a minute.
  void report(ErrorKind kind, const std::string& error);
  const std::vector<std::string>& errors() const { return errors_; }
  // Not an error, but worth a line: "note: ..." on stderr, the first time it is noted (an item that
  // comes round again does not repeat it).
  void note(const std::string& text);

  // The state to systemd at once (it sends only changes).
  void announce_state() { service_.state(kiosk_.name()); }
  // True when the status is due: forced (a change), or two seconds since the last.
  bool due(bool force);
  // The LEDs from the kiosk state; `lasting_warning`: see KioskState::set_lasting_warning.
  void set_leds(bool lasting_warning);
  // The LEDs, then the status file: `report` comes with item, frames, warnings and the self-check
  // filled in; the state, frame times and errors are added here.
  // `item`: the playlist's index of the item on screen (-1: none), for the metrics.
  void publish(hal::StatusReport report, int item = -1);

  // --metrics (or the board's metrics_file): written beside the status file at each publish().
  // `base`: the figures that do not change while the player runs (version, platform, renderer, start).
  void open_metrics(const std::string& path, const Metrics& base);
  void gpu_reset_survived(std::uint64_t resets) { metrics_.gpu_resets = resets; }
  // Whether a display is there (platform::Platform::presenting, display lost and found), whatever the
  // state: a display switched off for the night is still connected.
  void set_display_connected(bool connected) { metrics_.display_connected = connected; }
  // Within the opening hours, or switched on by a command.
  void set_open(bool open) { metrics_.open = open; }
  void scene_loaded(double seconds) { metrics_.scene_load_seconds = seconds; }

  // --log: the file (appended to when a session plays on after a GPU reset).
  void open_log(const std::string& path, bool append);
  // A button action, for the log line of the frame it acts on.
  void note_action(hal::Action action);
  // A control command that is no button's action ("resume", "reload", "item=2"), in the same field.
  void note_action(std::string_view name);
  // After a presented frame: its log line (when logging) and its time for the statistics.
  void frame_presented(const FrameLogLine& line);

  // systemd's watchdog and stop (board/ssao-player.service).
  ServiceNotifier& service() { return service_; }

 private:
  hal::Status& board_;
  KioskState& kiosk_;
  const PlayClock& clock_;
  std::ostream& err_;
  ServiceNotifier service_;
  std::optional<size_t> status_led_, error_led_;
  std::vector<std::string> errors_;
  std::unordered_set<std::string> notes_;  // one per item key at most: a set, for 100,000-item playlists
  double last_status_s_ = -1e9;
  std::string last_status_error_;
  FrameStats stats_;
  double last_frame_s_ = -1.0;
  std::ofstream log_;
  std::string pending_actions_;
  std::string metrics_path_, last_metrics_error_;
  Metrics metrics_;
  PlayClock::Steady::time_point last_log_ = PlayClock::Steady::now();
};

}  // namespace app
