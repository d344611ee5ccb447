#include "render/settings.h"

#include "base/parse.h"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace render {
namespace {

using base::parse_int;

bool parse_non_negative(std::string_view text, float& out) {
  float value = 0.0f;
  if (!base::parse_number(text, value) || value < 0.0f) return false;
  out = value;
  return true;
}

bool parse_on_off(std::string_view text, bool& out) {
  if (text == "on")
    out = true;
  else if (text == "off")
    out = false;
  else
    return false;
  return true;
}

std::string on_off(bool on) {
  return on ? "on" : "off";
}

std::string float_text(float value) {
  char text[32];
  const auto [end, ec] = std::to_chars(text, text + sizeof text, value);
  return ec == std::errc() ? std::string(text, end) : "0";
}

template <typename Enum>
bool parse_enum(std::span<const names::Named<Enum>> table, std::string_view text, Enum& out) {
  const auto parsed = names::parse(table, text);
  if (!parsed) return false;
  out = *parsed;
  return true;
}

// One row per key: how to read and write it. The table is the codec; --help and the validators
// are generated from it.
struct Row {
  struct {
    std::string_view key, help, choices;  // choices empty: those of the enum's name table (below)
  } key;
  std::string (*enum_choices)();
  bool (*set)(FrameSettings&, std::string_view);
  std::string (*get)(const FrameSettings&);
};

static_assert(TEMPORAL_MOVING_FRAMES == 8, "the help of `history` names the moving limit");

const Row kRows[] = {
    {{"ao", "Ambient occlusion on or off", "on|off"},
     nullptr,
     [](FrameSettings& s, std::string_view v) { return parse_on_off(v, s.ao); },
     [](const FrameSettings& s) { return on_off(s.ao); }},
    {{"estimator", "AO estimator: sphere (the paper, Mittring), hemisphere (cosine-weighted about the normal), horizon (GTAO)",
      ""},
     [] { return names::choices<ssao::Estimator>(ssao::kEstimatorNames); },
     [](FrameSettings& s, std::string_view v) {
       return parse_enum<ssao::Estimator>(ssao::kEstimatorNames, v, s.ao_settings.estimator);
     },
     [](const FrameSettings& s) { return std::string(ssao::name(s.ao_settings.estimator)); }},
    {{"precision",
      "AO per-sample arithmetic: highp (32-bit) or mediump (fp16 where the GPU has it, as embedded GPUs run it; the horizon "
      "estimator keeps its taps highp)",
      ""},
     [] { return names::choices<ssao::Precision>(ssao::kPrecisionNames); },
     [](FrameSettings& s, std::string_view v) {
       return parse_enum<ssao::Precision>(ssao::kPrecisionNames, v, s.ao_settings.precision);
     },
     [](const FrameSettings& s) { return std::string(ssao::name(s.ao_settings.precision)); }},
    {{"samples", "AO samples per radius (horizon: taps per pixel, 2 x steps per slice)", "1..64"},
     nullptr,
     [](FrameSettings& s, std::string_view v) { return parse_int(v, 1, SSAO_MAX_SAMPLES, s.ao_settings.samples); },
     [](const FrameSettings& s) { return std::to_string(s.ao_settings.samples); }},
    {{"steps",
      "Horizon estimator: taps on each side of a slice, the first 1.6 pixels out, the rest evenly to the radius (slices = "
      "samples / (2 x steps); at most samples / 2)",
      "1..32"},
     nullptr,
     [](FrameSettings& s, std::string_view v) { return parse_int(v, 1, SSAO_MAX_SAMPLES / 2, s.ao_settings.steps); },
     [](const FrameSettings& s) { return std::to_string(s.ao_settings.steps); }},
    {{"radii", "AO radii (multi-resolution, merged by max)", "1..5"},
     nullptr,
     [](FrameSettings& s, std::string_view v) { return parse_int(v, 1, SSAO_MAX_RADII, s.ao_settings.radii); },
     [](const FrameSettings& s) { return std::to_string(s.ao_settings.radii); }},
    {{"radius", "Largest AO radius in scene units (0: a tenth of the scene's bounding radius)", "a number >= 0"},
     nullptr,
     [](FrameSettings& s, std::string_view v) { return parse_non_negative(v, s.radius); },
     [](const FrameSettings& s) { return float_text(s.radius); }},
    {{"pattern", "Sample pattern of the sphere and hemisphere kernels (the horizon spaces its slices evenly)", ""},
     [] { return names::choices<ssao::Pattern>(ssao::kPatternNames); },
     [](FrameSettings& s, std::string_view v) {
       return parse_enum<ssao::Pattern>(ssao::kPatternNames, v, s.ao_settings.pattern);
     },
     [](const FrameSettings& s) { return std::string(ssao::name(s.ao_settings.pattern)); }},
    {{"ao-strength", "Power on 1 - AO in the shaded image (1: the AO as computed; the AO view is never changed)", "0..8"},
     nullptr,
     [](FrameSettings& s, std::string_view v) {
       float value = 0.0f;
       if (!parse_non_negative(v, value) || value > 8.0f) return false;
       s.ao_strength = value;
       return true;
     },
     [](const FrameSettings& s) { return float_text(s.ao_strength); }},
    {{"blur", "AO blur", ""},
     [] { return names::choices<ssao::Blur>(ssao::kBlurNames); },
     [](FrameSettings& s, std::string_view v) { return parse_enum<ssao::Blur>(ssao::kBlurNames, v, s.blur.mode); },
     [](const FrameSettings& s) { return std::string(ssao::name(s.blur.mode)); }},
    {{"resolution", "AO resolution: full, or half with depth-aware upsampling", "full|half"},
     nullptr,
     [](FrameSettings& s, std::string_view v) {
       if (v != "full" && v != "half") return false;
       s.ao_settings.half_resolution = v == "half";
       return true;
     },
     [](const FrameSettings& s) { return std::string(s.ao_settings.half_resolution ? "half" : "full"); }},
    {{"depth-chain", "Large radii read a downsampled depth chain", "on|off"},
     nullptr,
     [](FrameSettings& s, std::string_view v) { return parse_on_off(v, s.ao_settings.depth_chain); },
     [](const FrameSettings& s) { return on_off(s.ao_settings.depth_chain); }},
    {{"skip-radii", "Skip radii under a quarter pixel or beyond the scene's size, per frame", "on|off"},
     nullptr,
     [](FrameSettings& s, std::string_view v) { return parse_on_off(v, s.ao_settings.skip_radii); },
     [](const FrameSettings& s) { return on_off(s.ao_settings.skip_radii); }},
    {{"skip-background", "Background pixels skip the AO estimator (off only to measure what that saves)", "on|off"},
     nullptr,
     [](FrameSettings& s, std::string_view v) { return parse_on_off(v, s.ao_settings.skip_background); },
     [](const FrameSettings& s) { return on_off(s.ao_settings.skip_background); }},
    {{"untextured-variant", "Untextured materials use the G-buffer variant without a texture fetch (off only to measure it)",
      "on|off"},
     nullptr,
     [](FrameSettings& s, std::string_view v) { return parse_on_off(v, s.untextured_variant); },
     [](const FrameSettings& s) { return on_off(s.untextured_variant); }},
    {{"reuse-ao",
      "Keep the last frame's AO while camera and scene stand still, once temporal has averaged history frames (off: recompute "
      "every frame, for timing)",
      "on|off"},
     nullptr,
     [](FrameSettings& s, std::string_view v) { return parse_on_off(v, s.reuse_static_ao); },
     [](const FrameSettings& s) { return on_off(s.reuse_static_ao); }},
    {{"temporal", "Accumulate AO over frames: samples turn each frame, the previous frames' AO is reprojected and averaged in",
      "on|off"},
     nullptr,
     [](FrameSettings& s, std::string_view v) { return parse_on_off(v, s.temporal); },
     [](const FrameSettings& s) { return on_off(s.temporal); }},
    {{"motion-vectors",
      "Animated scenes: the temporal pass follows each pixel's own motion from the previous pose (off: the camera's alone)",
      "on|off"},
     nullptr,
     [](FrameSettings& s, std::string_view v) { return parse_on_off(v, s.motion_vectors); },
     [](const FrameSettings& s) { return on_off(s.motion_vectors); }},
    {{"present-tiles",
      "Shade only the screen tiles that hold a surface and fill the rest with the background (off: shade every pixel, to "
      "measure it)",
      "on|off"},
     nullptr,
     [](FrameSettings& s, std::string_view v) { return parse_on_off(v, s.present_tiles); },
     [](const FrameSettings& s) { return on_off(s.present_tiles); }},
    {{"history", "Frames the temporal accumulation averages at most (8 at most while the camera moves)", "1..255"},
     nullptr,
     [](FrameSettings& s, std::string_view v) { return parse_int(v, 1, 255, s.history); },
     [](const FrameSettings& s) { return std::to_string(s.history); }},
    {{"prepass", "Depth prepass before the G-buffer: on, off, or auto (measure both, keep the faster)", ""},
     [] { return names::choices<Prepass>(kPrepassNames); },
     [](FrameSettings& s, std::string_view v) { return parse_enum<Prepass>(kPrepassNames, v, s.prepass); },
     [](const FrameSettings& s) { return std::string(name(s.prepass)); }},
    {{"view", "What to show: the shaded image or a debug output", ""},
     [] { return names::choices<Picture>(kPictureNames); },
     [](FrameSettings& s, std::string_view v) { return parse_enum<Picture>(kPictureNames, v, s.output); },
     [](const FrameSettings& s) { return std::string(name(s.output)); }},
};

std::string choices_of(const Row& row) {
  return row.enum_choices != nullptr ? row.enum_choices() : std::string(row.key.choices);
}

const SettingKey* key_table() {
  static const auto table = [] {
    std::array<SettingKey, std::size(kRows)> keys{};
    for (size_t i = 0; i < std::size(kRows); ++i) keys[i] = {kRows[i].key.key, kRows[i].key.help, choices_of(kRows[i])};
    return keys;
  }();
  return table.data();
}

const Row* find(std::string_view key) {
  for (const Row& row : kRows)
    if (row.key.key == key) return &row;
  return nullptr;
}

std::string known_keys() {
  std::string text;
  for (const Row& row : kRows) text += std::string(text.empty() ? "" : ", ") + std::string(row.key.key);
  return text;
}

}  // namespace

std::string_view name(Picture output) {
  return names::name_of<Picture>(kPictureNames, output);
}
std::string_view name(Prepass prepass) {
  return names::name_of<Prepass>(kPrepassNames, prepass);
}

std::span<const SettingKey> setting_keys() {
  return {key_table(), std::size(kRows)};
}

bool apply_setting(FrameSettings& settings, std::string_view key, std::string_view value, std::string& error) {
  const Row* row = find(key);
  if (row == nullptr) {
    error = "unknown setting '" + std::string(key) + "' (expected one of " + known_keys() + ")";
    return false;
  }
  FrameSettings changed = settings;
  if (!row->set(changed, value)) {
    error = std::string(key) + ": expected " + choices_of(*row) + ", got '" + std::string(value) + "'";
    return false;
  }
  settings = changed;
  return true;
}

bool validate_setting(std::string_view key, std::string_view value, std::string& error) {
  FrameSettings scratch;
  return apply_setting(scratch, key, value, error);
}

std::string setting_value(const FrameSettings& settings, std::string_view key) {
  const Row* row = find(key);
  return row == nullptr ? std::string() : row->get(settings);
}

bool apply_settings(FrameSettings& settings, std::string_view list, std::string& error) {
  while (!list.empty()) {
    const size_t comma = list.find(',');
    const std::string_view item = list.substr(0, comma);
    const size_t equals = item.find('=');
    if (equals == std::string_view::npos) {
      error = "'" + std::string(item) + "' is not key=value";
      return false;
    }
    if (!apply_setting(settings, item.substr(0, equals), item.substr(equals + 1), error)) return false;
    list = comma == std::string_view::npos ? std::string_view() : list.substr(comma + 1);
  }
  return true;
}

std::string describe(const FrameSettings& settings, const FrameSettings& base) {
  std::string text;
  for (const Row& row : kRows) {
    const std::string value = row.get(settings);
    if (value == row.get(base)) continue;
    text += (text.empty() ? "" : ",") + std::string(row.key.key) + "=" + value;
  }
  return text;
}

}  // namespace render
