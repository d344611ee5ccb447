#include "play/metrics_file.h"

#include "base/names.h"

#include <charconv>
#include <cmath>

namespace app {
namespace {

constexpr base::Name<ErrorKind> kErrorKindNames[] = {
    {ErrorKind::content, "content"}, {ErrorKind::display, "display"},       {ErrorKind::gpu, "gpu"},
    {ErrorKind::device, "device"},   {ErrorKind::self_check, "self_check"}, {ErrorKind::service, "service"},
    {ErrorKind::control, "control"},
};
static_assert(base::in_enum_order(kErrorKindNames));
static_assert(std::size(kErrorKindNames) == kErrorKinds);

// A label value as the format wants it: backslash, double quote and line feed escaped.
std::string label(std::string_view value) {
  std::string out;
  for (const char c : value) {
    if (c == '\\' || c == '"')
      out += {'\\', c};
    else if (c == '\n')
      out += "\\n";
    else
      out += c;
  }
  return out;
}

// The shortest text that reads back as the same double.
std::string number(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "+Inf" : "-Inf";
  char text[32];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, v);
  return ec == std::errc() ? std::string(text, end) : "NaN";
}

void family(std::string& out, std::string_view name, std::string_view type, std::string_view help) {
  out.append("# HELP ").append(name).append(" ").append(help).append("\n");
  out.append("# TYPE ").append(name).append(" ").append(type).append("\n");
}

void sample(std::string& out, std::string_view name, std::string_view labels, double value) {
  out.append(name);
  if (!labels.empty()) out.append("{").append(labels).append("}");
  out.append(" ").append(number(value)).append("\n");
}

}  // namespace

std::string_view name(ErrorKind kind) {
  return base::name_of(kErrorKindNames, kind);
}

std::string format_metrics(const Metrics& m) {
  std::string out;
  family(out, "ssao_player_info", "gauge", "The player's version, platform and GL renderer; always 1.");
  sample(out, "ssao_player_info",
         "version=\"" + label(m.version) + "\",platform=\"" + label(m.platform) + "\",renderer=\"" + label(m.renderer) + "\"", 1);
  family(out, "ssao_player_start_time_seconds", "gauge", "When the player started, in seconds since the Unix epoch.");
  sample(out, "ssao_player_start_time_seconds", "", m.start_unix_s);
  family(out, "ssao_player_state", "gauge", "The player's state: 1 for the one it is in, 0 for the others.");
  for (const std::string_view state : kStates)
    sample(out, "ssao_player_state", "state=\"" + std::string(state) + "\"", state == m.state ? 1 : 0);
  family(out, "ssao_player_item", "gauge", "The playlist's item on screen, counted from 0; -1 when none is.");
  sample(out, "ssao_player_item", "", m.item);
  if (m.item >= 0) {
    family(out, "ssao_player_item_info", "gauge", "The scene of the item on screen; always 1.");
    sample(out, "ssao_player_item_info", "scene=\"" + label(m.scene) + "\"", 1);
  }
  family(out, "ssao_player_frames_total", "counter", "Frames presented since the start.");
  sample(out, "ssao_player_frames_total", "", static_cast<double>(m.frames));
  family(out, "ssao_player_frame_seconds", "summary",
         "Time from one presented frame to the next: quantiles over the recent 256, sum and count since the start.");
  sample(out, "ssao_player_frame_seconds", "quantile=\"0.5\"", m.frame_seconds_p50);
  sample(out, "ssao_player_frame_seconds", "quantile=\"0.99\"", m.frame_seconds_p99);
  sample(out, "ssao_player_frame_seconds_sum", "", m.frame_seconds_sum);
  sample(out, "ssao_player_frame_seconds_count", "", static_cast<double>(m.frame_intervals));
  family(out, "ssao_player_errors_total", "counter", "Errors reported since the start, by what they are about.");
  for (std::size_t k = 0; k < kErrorKinds; ++k)
    sample(out, "ssao_player_errors_total", "kind=\"" + std::string(name(static_cast<ErrorKind>(k))) + "\"",
           static_cast<double>(m.errors[k]));
  if (m.self_check) {
    family(out, "ssao_player_self_check_passed", "gauge", "Whether the last display self-check passed (1) or failed (0).");
    sample(out, "ssao_player_self_check_passed", "", m.self_check->passed ? 1 : 0);
    family(out, "ssao_player_self_check_score", "gauge", "The last self-check's agreement of camera and frame, 0 to 1.");
    sample(out, "ssao_player_self_check_score", "", m.self_check->score);
    family(out, "ssao_player_self_check_timestamp_seconds", "gauge",
           "When the last self-check finished, in seconds since the Unix epoch.");
    sample(out, "ssao_player_self_check_timestamp_seconds", "", m.self_check->unix_s);
  }
  if (m.scene_load_seconds) {
    family(out, "ssao_player_scene_load_seconds", "gauge",
           "How long the last scene took from its request to being ready to upload (read, decoded, checked).");
    sample(out, "ssao_player_scene_load_seconds", "", *m.scene_load_seconds);
  }
  family(out, "ssao_player_resident_memory_bytes", "gauge", "The player's resident memory.");
  sample(out, "ssao_player_resident_memory_bytes", "", static_cast<double>(m.resident_bytes));
  family(out, "ssao_player_display_connected", "gauge",
         "Whether a display is there to show the frames (1) or none is (0); switched off while closed, it is still there.");
  sample(out, "ssao_player_display_connected", "", m.display_connected ? 1 : 0);
  family(out, "ssao_player_open", "gauge",
         "Whether the board's opening hours (and a display on|off command) have the display on (1) or off (0).");
  sample(out, "ssao_player_open", "", m.open ? 1 : 0);
  family(out, "ssao_player_gpu_resets_total", "counter", "GPU contexts lost and made anew since the start.");
  sample(out, "ssao_player_gpu_resets_total", "", static_cast<double>(m.gpu_resets));
  return out;
}

}  // namespace app
