#pragma once
// Opens a board's devices with the chosen backend. Whatever is missing is reported in `problems` and
// left out (or, for the camera, retried); the player goes on with the rest.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hal/board.h"
#include "hal/buttons.h"
#include "hal/camera.h"
#include "hal/status.h"

namespace hal {

class MockButtons;
class MockCamera;

enum class Backend : std::uint8_t { linux_kernel, mock };
bool parse_backend(std::string_view text, Backend& out);
std::string_view to_string(Backend backend);
std::vector<std::string> backend_names();  // {"linux", "mock"}, for --hal

struct Devices {
  std::unique_ptr<Buttons> buttons;  // never null; a button whose line is missing never fires
  std::unique_ptr<Status> status;    // never null; a missing LED is skipped
  std::unique_ptr<Camera> camera;    // null only when the board has no camera
  std::vector<std::string> problems;
  // The mock backend's devices again (null with linux), for what drives them: a window's keys, a
  // test's camera script, the frame the synthetic camera films.
  MockButtons* mock_buttons = nullptr;
  MockCamera* mock_camera = nullptr;
};

Devices open_devices(const BoardConfig& board, Backend backend, const Clock& clock);

// The linux backends, also usable on their own. Missing lines are appended to `problems`.
std::unique_ptr<Buttons> open_gpio_buttons(const std::vector<ButtonConfig>& buttons, const std::string& consumer,
                                           const Clock& clock, std::vector<std::string>& problems);
// The GPIO buttons plus keyboards: a key whose name is a button's `key` (board_key_name) presses
// that button, from any evdev keyboard in `input_dir`, also one plugged in later. open_devices uses it.
std::unique_ptr<Buttons> open_linux_buttons(const std::vector<ButtonConfig>& buttons, const std::string& consumer,
                                            const Clock& clock, std::vector<std::string>& problems,
                                            const std::string& input_dir = "/dev/input");
std::unique_ptr<LedSink> open_gpio_leds(const std::vector<LedConfig>& leds, const std::string& consumer,
                                        std::vector<std::string>& problems);
// Never null: a device that cannot be opened yields a camera in state Lost that retries. `clock` times
// the reopen and no-frame deadlines.
std::unique_ptr<Camera> open_v4l2_camera(const CameraConfig& config, const Clock& clock);

}  // namespace hal
