#pragma once
// What a frame is rendered with, and the one key=value codec that the command line, playlists and
// aobench share: every key is the command line's long option without its dashes, and every enum's
// names come from one table. Pure: no GL.
//
// Errors: functions return false and say what was expected in `error`; nothing throws.
#include "ssao/names.h"
#include "ssao/params.h"

#include <glm/glm.hpp>

#include <span>
#include <string>
#include <string_view>

namespace render {

// The picture the present pass makes (setting `output`): the shaded image, or a debug view of the
// AO, the normals or the depth. Not to be confused with render::Output, where frames go.
enum class Picture { color, ao, normal, depth };
inline constexpr names::Named<Picture> kPictureNames[] = {
    {Picture::color, "color"}, {Picture::ao, "ao"}, {Picture::normal, "normal"}, {Picture::depth, "depth"}};

// The depth prepass pays only where overdraw is high enough that shading fragments twice costs more
// than drawing the geometry twice; `automatic` measures both on the first two frames and keeps the faster.
enum class Prepass { off, on, automatic };
inline constexpr names::Named<Prepass> kPrepassNames[] = {
    {Prepass::on, "on"}, {Prepass::off, "off"}, {Prepass::automatic, "auto"}};

std::string_view name(Picture output);
std::string_view name(Prepass prepass);

struct FrameSettings {
  int width = 1024, height = 768;
  bool ao = true;
  ssao::AoSettings ao_settings;
  ssao::BlurSettings blur;
  float radius = 0.0f;  // base AO radius in world units; 0: a tenth of the scene's bounding radius
  Picture output = Picture::color;
  Prepass prepass = Prepass::automatic;
  bool reuse_static_ao = true;  // while camera and scene stand still, keep the last frame's AO
  // Temporal accumulation: each frame turns its AO samples anew and averages them with the previous
  // frames' AO found by reprojection; `history` frames at most (TEMPORAL_MOVING_FRAMES while the
  // camera moves). With reuse_static_ao, a still camera stops computing AO once it has `history`.
  bool temporal = true;
  // In an animated scene, the temporal pass follows each pixel's own motion (a motion target the
  // G-buffer writes from the previous pose), not the camera's alone. Off only to measure what it
  // saves (aobench --ghosting): history is then found where the camera alone puts it.
  bool motion_vectors = true;
  // The present pass shades only the tiles of the view that hold a surface (a compute pass lists
  // them from the G-buffer's depth) and fills the rest with the background: llvmpipe shades every
  // pixel a draw covers, background or not. Off only to measure what it saves; light field modules
  // always shade their whole (small) view.
  bool present_tiles = true;
  // The shaded image's visibility is (1 - AO)^ao_strength; the AO itself (the AO view, dumps,
  // aobench) is never changed by it.
  float ao_strength = 1.0f;
  int history = 32;
  // Untextured materials draw with the G-buffer variant that fetches no texture. Off only to measure
  // what that saves (aobench's untextured-variant=off): they then sample a 1x1 white texture.
  bool untextured_variant = true;
  glm::vec3 background{0.05f, 0.06f, 0.08f};  // linear RGB of empty pixels
  // The light: the environment (the scene's, or the built-in studio) scaled by environment_intensity,
  // and the key light, a directional light fixed to the camera (from the upper left, in front) of
  // irradiance key_light (0: none).
  float environment_intensity = 1.0f;
  float key_light = 1.0f;
  bool check_errors = false;  // glGetError after each pass (tests, debug runs)
};

// One key of the codec.
struct SettingKey {
  std::string_view key;   // also the long option: --key
  std::string_view help;  // for --help
  std::string choices;    // "on|off", "1..64", ...: what a value must be
};
std::span<const SettingKey> setting_keys();

// Sets one key from its text. Unknown key or bad value: false, and `error` says
// "<key>: expected <what>, got '<value>'".
bool apply_setting(FrameSettings& settings, std::string_view key, std::string_view value, std::string& error);
// The current value of `key` as apply_setting() reads it back ("" for an unknown key).
std::string setting_value(const FrameSettings& settings, std::string_view key);
// "key=value,key=value": each applied in turn; the first failure is reported.
bool apply_settings(FrameSettings& settings, std::string_view list, std::string& error);
// The keys whose values differ from `base`, as "key=value,..." (empty when none differ).
std::string describe(const FrameSettings& settings, const FrameSettings& base);
// The same without applying: whether `value` is valid for `key`.
bool validate_setting(std::string_view key, std::string_view value, std::string& error);

}  // namespace render
