#include "hal/devices.h"
#include "base/read_file.h"

#include <fstream>
#include <sstream>

#include "base/names.h"
#include "hal/mock.h"

namespace hal {

namespace {
constexpr base::Name<Backend> kBackendNames[] = {{Backend::linux_kernel, "linux"}, {Backend::mock, "mock"}};
static_assert(base::in_enum_order(kBackendNames));
}  // namespace

bool parse_backend(std::string_view text, Backend& out) {
  return base::parse_name(kBackendNames, text, out);
}
std::string_view to_string(Backend backend) {
  return base::name_of(kBackendNames, backend);
}
std::vector<std::string> backend_names() {
  return base::names_of(kBackendNames);
}

CameraModel typical_camera_model() {
  CameraModel m;
  m.screen_corners = {{{70, 90}, {575, 100}, {565, 390}, {80, 400}}};
  m.blur_sigma = 0.8;
  m.noise_sigma = 2.0;
  m.exposure = 0.9;
  m.gamma = 1.1;
  m.vignetting = 0.2;
  return m;
}

Devices open_devices(const BoardConfig& board, Backend backend, const Clock& clock) {
  Devices d;
  std::vector<std::string> led_names;
  for (const auto& l : board.leds) led_names.push_back(l.name);

  if (backend == Backend::linux_kernel) {
    d.buttons = open_linux_buttons(board.buttons, board.consumer, clock, d.problems);
    d.status =
        std::make_unique<Status>(led_names, open_gpio_leds(board.leds, board.consumer, d.problems), clock, board.status_file);
    if (board.camera) {
      d.camera = open_v4l2_camera(*board.camera, clock);
      if (d.camera->state() != CameraState::streaming) d.problems.push_back("camera: " + d.camera->last_error());
    }
    return d;
  }

  std::vector<MockButtonSpec> specs;
  for (const auto& b : board.buttons) specs.push_back({b.name, b.timing});
  std::vector<ScriptStep> script;
  if (!board.mock_button_script.empty()) {
    std::string text, error;
    if (!base::read_regular_file(board.mock_button_script, "button script", kMaxScriptBytes, text, error))
      throw ConfigError(board.source + ": mock.button_script: " + error);
    script = parse_button_script(text, board.mock_button_script);
  }
  auto buttons = std::make_unique<MockButtons>(std::move(specs), std::move(script), clock);
  d.mock_buttons = buttons.get();
  d.buttons = std::move(buttons);
  d.status =
      std::make_unique<Status>(led_names, std::make_unique<RecordingLedSink>(clock, led_names.size()), clock, board.status_file);
  std::unique_ptr<MockCamera> camera;
  if (!board.mock_camera_images.empty()) {
    camera = std::make_unique<MockCamera>(board.mock_camera_images, clock);
  } else if (board.camera) {
    camera = std::make_unique<MockCamera>(typical_camera_model(), clock);
  }
  d.mock_camera = camera.get();
  d.camera = std::move(camera);
  return d;
}

}  // namespace hal
