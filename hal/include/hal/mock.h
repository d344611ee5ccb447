#pragma once
// Mock devices: scripted buttons, recorded LEDs, a camera that reads image files or renders what a
// real camera would see of a given displayed frame.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "base/unique_fd.h"
#include "hal/buttons.h"
#include "hal/camera.h"
#include "hal/status.h"

namespace hal {

// One line of a button script: at `at` after the start, the raw level of `button` changes.
struct ScriptStep {
  Nanos at{0};
  std::string button;
  bool pressed = false;
};

// Script format, one step a line, '#' starts a comment:
//   <milliseconds> <button name> press|release
// Times are from the start of the script and must not decrease. Bounce is written as quick
// press/release pairs. Throws ConfigError naming the file, line and field.
std::vector<ScriptStep> parse_button_script(const std::string& text, const std::string& source_name);

struct MockButtonSpec {
  std::string name;
  ButtonTiming timing;
};

class MockButtons final : public Buttons {
 public:
  MockButtons(std::vector<MockButtonSpec> buttons, std::vector<ScriptStep> script, const Clock& clock);
  ~MockButtons() override;
  int fd() const override;
  std::size_t count() const override;
  std::string_view name(std::size_t button) const override;
  std::size_t read(std::span<ButtonEvent> out) override;
  std::size_t dropped() const override;
  const std::string& last_error() const override;  // always empty: a script cannot fail
  // Raw level change now: what keys of a desktop window would send (no window platform exists yet;
  // tests use it).
  void inject(std::size_t button, bool pressed);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Records every level change with its time, for tests and for hal-test's printout.
class RecordingLedSink final : public LedSink {
 public:
  struct Change {
    std::size_t led;
    bool on;
    Nanos time;
  };
  explicit RecordingLedSink(const Clock& clock, std::size_t leds) : clock_(clock), levels_(leds, false) {}
  void set(std::size_t led, bool on) override;
  // Shared so a test can keep reading it after the sink moved into a Status.
  std::shared_ptr<std::vector<Change>> changes = std::make_shared<std::vector<Change>>();

 private:
  const Clock& clock_;
  std::vector<bool> levels_;
};

// How the mock camera sees the display.
struct CameraModel {
  int width = 640;
  int height = 480;
  // Display pixel (x, y, 1) -> camera pixel, row-major 3x3; pixel centres at integer coordinates.
  std::array<double, 9> homography{1, 0, 0, 0, 1, 0, 0, 0, 1};
  // When set, replaces `homography`: the screen's corners (top-left, top-right, bottom-right,
  // bottom-left) in camera pixels, whatever size the displayed frame has.
  std::optional<std::array<std::array<double, 2>, 4>> screen_corners;
  double blur_sigma = 0.0;     // lens blur, camera pixels
  double noise_sigma = 0.0;    // additive Gaussian noise, 8-bit levels
  double exposure = 1.0;       // linear gain
  double gamma = 1.0;          // output = (exposure * input)^(1/gamma)
  double vignetting = 0.0;     // brightness falls by this fraction at the image corners
  std::uint8_t surround = 12;  // what lies around the screen
  std::uint32_t seed = 1;      // noise is deterministic for a seed
};

// A webcam on a stand in front of the screen: slightly off-axis, blurred, noisy, darker at the edges.
CameraModel typical_camera_model();

// A homography placing a display of the given size in the camera image with its four corners at
// `corners` (top-left, top-right, bottom-right, bottom-left), camera pixels.
std::array<double, 9> homography_for_corners(int display_w, int display_h, const std::array<std::array<double, 2>, 4>& corners);

// Renders what the camera would capture of `displayed`. `noise_frame` varies the noise per frame.
void synthesize_capture(const RgbImage& displayed, const CameraModel& model, std::uint32_t noise_frame, RgbImage& out);

// A deterministic stand-in for a rendered frame: sky gradient, ground plane, shaded spheres and boxes.
// `scene` picks the layout and colours, `t` (seconds) moves the objects as playback would.
RgbImage make_test_scene(int width, int height, int scene, double t);

// Delivers a frame every `frame_interval` of `clock`, as a webcam does: fd() (a timerfd) is readable
// exactly when read_frame() has a frame (or, after unplug()/replug(), when service() has something
// to do), so a poll loop neither spins nor misses frames.
class MockCamera final : public Camera {
 public:
  static constexpr Nanos kFrameInterval = std::chrono::nanoseconds(1'000'000'000 / 30);  // 30 fps

  // Frames cycle through image files (loaded once, at construction); the first is due at once.
  MockCamera(const std::vector<std::string>& image_files, const Clock& clock, Nanos frame_interval = kFrameInterval);
  // Frames are synthesised from whatever show() was last given; the first is due when show() is called.
  MockCamera(CameraModel model, const Clock& clock, Nanos frame_interval = kFrameInterval);

  void show(const RgbImage& displayed);  // what the display presents now
  void unplug();                         // acts like ENODEV: state Lost until replug()
  void replug();

  int fd() const override;
  CameraState state() const override { return state_; }
  const std::string& last_error() const override { return error_; }
  bool read_frame(RgbImage& out) override;
  void service() override;

 private:
  bool has_source() const { return !synthetic_ || !displayed_.empty(); }
  void arm(Nanos at);

  std::vector<RgbImage> files_;
  std::size_t next_file_ = 0;
  CameraModel model_;
  bool synthetic_ = false;
  RgbImage displayed_;
  std::uint32_t frame_ = 0;
  CameraState state_ = CameraState::streaming;
  bool plugged_ = true;
  std::string error_;
  const Clock& clock_;
  Nanos interval_;
  Nanos next_frame_{0};
  base::UniqueFd timer_;
};

}  // namespace hal
