#pragma once
// A board description: which GPIO lines are buttons and LEDs, which camera watches the display.
// Read from TOML; see board/README.md for the format.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "hal/buttons.h"
#include "hal/camera.h"
#include "hal/opening_hours.h"

namespace hal {

enum class Bias : std::uint8_t { as_is, disable, pull_up, pull_down };

// A GPIO line, by line name (stable across Pi 4 and Pi 5, e.g. "GPIO17") or by chip + offset.
struct GpioLine {
  std::string chip;  // name ("gpiochip0"), path, label or number, as gpiod_chip_open_lookup takes
  int offset = -1;
  std::string line_name;
  bool active_low = false;
  Bias bias = Bias::as_is;
  std::string describe() const;  // "line GPIO17" or "gpiochip0:17", for error messages
};

// What a button does in the player. The board file names them; hal only checks the names.
enum class Action : std::uint8_t { none, next, previous, pause, ao, output, restart, check };
std::string_view to_string(Action a);
bool parse_action(std::string_view text, Action& out);
// "none, next, ..." for messages and docs.
std::string action_names();

struct ButtonConfig {
  std::string name;
  GpioLine line;
  ButtonTiming timing;
  // Defaults by name: play -> pause (long press: restart), next -> next, previous -> previous,
  // check -> check; any other name does nothing until the board file says `action`.
  Action action = Action::none;
  Action long_action = Action::none;
  // The desktop key that stands in for this button in the window platform (SDL key names in lower
  // case: "space", "n", "right"); defaults: play "space", next "n", previous "p", check "c".
  std::string key;
};

struct LedConfig {
  std::string name;
  GpioLine line;
};

struct BoardConfig {
  std::string source;  // the file it came from, for messages
  std::string name;
  std::string consumer = "ssao-player";  // shown by gpioinfo as the line's user
  std::vector<ButtonConfig> buttons;
  std::vector<LedConfig> leds;
  std::optional<CameraConfig> camera;
  std::string status_file;
  std::string control;               // the control socket's path (player ctl, the fleet agent); empty: none
  std::string metrics_file;          // Prometheus textfile-collector file; empty: none
  double self_check_interval_s = 0;  // the player's display self-check period; 0: only on demand
  // [display] rotation: how far the player turns its frames (clockwise, as seen) for a display mounted
  // turned; done by the renderer, since many boards cannot rotate the scanout. 0, 90, 180 or 270.
  int display_rotation = 0;
  // [schedule]: the opening hours; none: always open.
  std::optional<OpeningHours> schedule;
  std::string mock_button_script;  // relative paths are resolved against the board file's folder
  std::vector<std::string> mock_camera_images;
};

// Thrown only while loading, never once running: "<file>: <field>: expected <what>, got <what>".
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The largest board file and mock script (button or camera) read, in bytes; anything else than a
// regular file is refused too (base/read_file.h).
inline constexpr std::size_t kMaxBoardFileBytes = 1u << 20;
inline constexpr std::size_t kMaxScriptBytes = 16u << 20;

BoardConfig load_board(const std::string& path);
// What a Pi with three buttons (play, next, check) and two LEDs (status, error) and a camera has;
// used when no board file is given.
BoardConfig builtin_mock_board();
BoardConfig parse_board(const std::string& toml_text, const std::string& source_name);

}  // namespace hal
