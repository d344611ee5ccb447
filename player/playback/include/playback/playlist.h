#pragma once
// The playlist: which scenes to play, for how long, with which camera and render settings.
//
// Errors: every function that can fail returns bool and fills `std::string& error` with one line
// naming the file, the position, the field and what was expected; nothing throws out of this
// library (toml++'s parse errors are caught inside).

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

namespace playback {

enum class Motion { still, turntable, orbit, file };
enum class Schedule { sequential, wallclock };

std::string_view name(Motion m);
std::string_view name(Schedule s);

// One keyframe of an orbit: at `t` seconds into the item the camera is at this pose. Azimuth is not
// wrapped between keys (0 -> 720 is two turns). Keys missing azimuth/elevation/distance take the
// camera table's values.
struct OrbitKey {
  double t{}, azimuth_deg{}, elevation_deg{}, distance{};  // the parser gives every field
};

struct CameraPath {
  Motion motion = Motion::turntable;
  double period_s = 20;        // turntable: seconds per turn
  double azimuth_deg = 30;     // start azimuth (turntable), the pose (still)
  double elevation_deg = 20;   // in [-89, 89]
  double distance = 1.0;       // multiple of the distance that fits the scene in view
  double fov_deg = 45;         // vertical field of view, in (1, 170)
  std::vector<OrbitKey> keys;  // orbit only: >= 2, t strictly increasing from 0
  int index = 0;               // file only: which of the scene's cameras (glTF's, in node order)
};

// A render setting from an item's `ao` table: key as written in the playlist (the command line's
// long option without dashes), value as the command line would take it.
struct Setting {
  std::string key, value;
  bool operator==(const Setting&) const = default;
};

struct Item {
  std::string scene;  // absolute, normalised path inside the content root, or "builtin:NAME" untouched
  double duration_s = 10;
  CameraPath camera;
  std::vector<Setting> settings;  // in the order they are written
  bool has_background = false;
  glm::vec3 background{};  // read only where has_background
  std::string display;     // light-field display description, resolved like `scene`; empty if none
  // What lights the scene: an equirectangular HDR/EXR resolved like `scene`, or builtin:studio;
  // empty: the player's default (--environment, else the built-in studio).
  std::string environment;
  // The scene's animations shown: "all" (together, looping over the longest), "none" (the rest
  // pose), a name, or an index as text; checked against the scene when it has loaded.
  std::string animation = "all";
  double animation_speed = 1.0;  // animation seconds per item second
  int line{};                    // where the item's table starts in the file, for messages
};

struct Playlist {
  std::string source;  // the file, or "command line"
  bool loop = true, shuffle = false;
  std::uint64_t seed = 1;  // the shuffle's seed
  double fade_s = 0.5;     // fade to black between items: out over fade_s/2, in over fade_s/2
  Schedule schedule = Schedule::sequential;
  std::vector<Item> items;
};

// Validates one render setting; returns false and says what was expected in `error`, starting
// with "expected" (e.g. "expected one of sphere, hemisphere, horizon"); the parser prefixes the
// position and field and appends ", got <value>".
using SettingValidator = std::function<bool(std::string_view key, std::string_view value, std::string& error)>;

struct ParseOptions {
  // Every scene and display path must resolve inside this folder (after normalisation and, for the
  // part of the path that exists, resolving symlinks). Empty: the playlist's folder. A relative
  // root is taken against the current directory.
  std::string content_root;
  SettingValidator validate_setting;  // null: accept any setting
  // The environment of items that name none (play --environment); empty: the built-in studio.
  std::string default_environment;
};

// Parses a playlist. `source_path` names the file in messages and is the folder relative paths
// resolve against. Scene files are not required to exist (the player skips a missing one when it
// loads it); only the content-root rule is checked. On failure `out` is left unchanged.
bool parse_playlist(std::string_view toml_text, const std::string& source_path, const ParseOptions& options, Playlist& out,
                    std::string& error);
// The largest playlist file read: 100,000 items of a few lines each are about 5 MB.
inline constexpr std::size_t kMaxPlaylistBytes = 64u << 20;
// Reads and parses a playlist file, a regular file of at most kMaxPlaylistBytes (base/read_file.h:
// "<file>: cannot open the playlist (<reason>)", "<file>: the playlist is a FIFO, not a regular file").
bool load_playlist(const std::string& path, const ParseOptions& options, Playlist& out, std::string& error);

// `player play SCENE...`: each scene (path as given) for `duration_s` on a turntable of `period_s`
// seconds per turn, looping, with the default fade.
Playlist playlist_from_scenes(const std::vector<std::string>& scenes, double duration_s, double period_s);

}  // namespace playback
