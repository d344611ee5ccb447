#pragma once
// The player's figures for Prometheus: a node_exporter textfile-collector file (`--metrics FILE`, or
// the board's metrics_file), replaced whole at every status period so a scrape never reads half of
// one. Names follow Prometheus' conventions (ssao_player_ prefix, base units, _total counters).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace app {

// What an error is about: ssao_player_errors_total{kind="..."}.
enum class ErrorKind : std::uint8_t { content, display, gpu, device, self_check, service, control };
inline constexpr std::size_t kErrorKinds = 7;
std::string_view name(ErrorKind kind);

struct Metrics {
  std::string version, platform, renderer;  // ssao_player_info's labels
  double start_unix_s = 0.0;
  std::string_view state;  // one of kStates below
  int item = -1;           // the playlist's item on screen, -1 for none
  std::string scene;       // its scene
  std::uint64_t frames = 0;
  // Frame-to-frame times: every interval since the start (sum, count) and the recent window's quantiles.
  double frame_seconds_sum = 0.0;
  std::uint64_t frame_intervals = 0;
  double frame_seconds_p50 = 0.0, frame_seconds_p99 = 0.0;
  std::array<std::uint64_t, kErrorKinds> errors{};
  struct Check {
    bool passed = false;
    double score = 0.0;
    double unix_s = 0.0;
  };
  std::optional<Check> self_check;           // none before the first one
  std::optional<double> scene_load_seconds;  // the last scene loaded, from request to ready
  std::uint64_t resident_bytes = 0;
  bool display_connected = false;
  bool open = true;  // within the board's opening hours (always, without a [schedule])
  std::uint64_t gpu_resets = 0;
};

// The states ssao_player_state{state="..."} lists, one of them 1: KioskState's states, in its order,
// named as label values are (no_display for "no display").
inline constexpr std::array<std::string_view, 7> kStates = {"starting", "loading",    "playing", "paused",
                                                            "error",    "no_display", "closed"};

// The exposition format (text 0.0.4), HELP and TYPE for each family.
std::string format_metrics(const Metrics& metrics);

}  // namespace app
