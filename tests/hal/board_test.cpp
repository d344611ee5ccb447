// Board files: the shipped ones parse, and errors name file, line and column, field, expectation and
// what was there.
#include <gtest/gtest.h>

#include "hal/board.h"

#ifndef HAL_SOURCE_DIR
#define HAL_SOURCE_DIR ""
#endif

namespace hal {
namespace {

std::string error_of(const std::string& toml) {
  try {
    parse_board(toml, "b.toml");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Board, ParsesButtonsLedsCameraAndDefaults) {
  const BoardConfig b = parse_board(R"(
[board]
name = "test"
status_file = "/run/x/status.json"
control = "/run/x/control"
metrics_file = "/var/lib/prometheus/node-exporter/ssao-player.prom"
[buttons]
debounce_ms = 30
[[button]]
name = "play"
line = "GPIO17"
active_low = true
bias = "pull-up"
[[button]]
name = "next"
chip = "gpiochip0"
offset = 27
repeat_delay_ms = 400
[[led]]
name = "status"
chip = "1"
offset = 3
[camera]
device = "/dev/v4l/by-id/usb-cam-video-index0"
format = "yuyv"
width = 640
height = 480
frame_timeout_ms = 500
[mock]
button_script = "buttons.script"
)",
                                    "/etc/player/board.toml");
  ASSERT_EQ(b.buttons.size(), 2u);
  EXPECT_EQ(b.buttons[0].line.line_name, "GPIO17");
  EXPECT_TRUE(b.buttons[0].line.active_low);
  EXPECT_EQ(b.buttons[0].line.bias, Bias::pull_up);
  EXPECT_EQ(b.buttons[0].timing.debounce, std::chrono::milliseconds(30));
  EXPECT_EQ(b.buttons[1].line.describe(), "gpiochip0:27");
  EXPECT_EQ(b.buttons[1].timing.repeat_delay, std::chrono::milliseconds(400));
  ASSERT_EQ(b.leds.size(), 1u);
  ASSERT_TRUE(b.camera.has_value());
  EXPECT_EQ(b.camera->format, PixelFormat::yuyv);
  EXPECT_EQ(b.camera->width, 640);
  EXPECT_EQ(b.camera->frame_timeout, std::chrono::milliseconds(500));
  EXPECT_EQ(b.camera->reopen_interval, std::chrono::milliseconds(2000));
  EXPECT_EQ(b.mock_button_script, "/etc/player/buttons.script");
  EXPECT_EQ(b.status_file, "/run/x/status.json");
  EXPECT_EQ(b.control, "/run/x/control");
  EXPECT_EQ(b.metrics_file, "/var/lib/prometheus/node-exporter/ssao-player.prom");
}

TEST(Board, ErrorsNameFileFieldAndExpectation) {
  EXPECT_EQ(error_of("[[button]]\nname = \"a\"\n"),
            "b.toml:1:1: button[0].line: expected a line name, or 'chip' and 'offset', got nothing");
  EXPECT_EQ(error_of("[[button]]\nname = \"a\"\nchip = \"gpiochip0\"\noffset = \"x\"\n"),
            "b.toml:4:10: button[0].offset: expected an integer in 0..1023, got 'x'");
  EXPECT_EQ(error_of("[[led]]\nname = \"a\"\nline = \"L\"\nbias = \"up\"\n"),
            "b.toml:4:8: led[0].bias: expected one of as-is, disable, pull-up, pull-down, got 'up'");
  EXPECT_EQ(error_of("[camera]\ndevice = \"/dev/video0\"\nformat = \"h264\"\n"),
            "b.toml:3:10: camera.format: expected one of auto, mjpeg, yuyv, rgb24, got 'h264'");
  EXPECT_EQ(error_of("[camera]\nwidth = 640\n"), "b.toml:1:1: camera.device: expected a string, got nothing");
  EXPECT_EQ(error_of("[camera]\ndevice = \"/dev/video0\"\nframe_timeout_ms = 0\n"),
            "b.toml:3:20: camera.frame_timeout_ms: expected an integer in 100..600000, got 0");
  EXPECT_EQ(error_of("button = 3\n"), "b.toml:1:10: button: expected an array of tables ([[button]]), got 3");
  EXPECT_EQ(error_of("[board\n").rfind("b.toml:1:", 0), 0u);
  EXPECT_THROW(load_board("/nonexistent/board.toml"), ConfigError);
}

// A key the format does not have is a typo or a misunderstanding, at any level: refused with its
// position and the keys that level has, as playlists and display files refuse theirs.
TEST(Board, RefusesUnknownKeysAtEveryLevel) {
  EXPECT_EQ(error_of("[board]\nname = \"kiosk\"\nbackend = \"linux\"\n"),
            "b.toml:3:11: board.backend: unknown key (expected one of name, consumer, status_file, control, metrics_file, "
            "self_check_interval_s)");
  EXPECT_EQ(error_of("backend = \"linux\"\n"),
            "b.toml:1:11: backend: unknown key (expected one of board, display, schedule, buttons, button, led, camera, mock)");
  EXPECT_EQ(error_of("[display]\nrotate = 90\n"), "b.toml:2:10: display.rotate: unknown key (expected one of rotation)");
  EXPECT_EQ(
      error_of("[buttons]\ndebounce = 30\n").rfind("b.toml:2:12: buttons.debounce: unknown key (expected one of debounce_ms,", 0),
      0u);
  EXPECT_EQ(error_of("[[button]]\nname = \"a\"\nline = \"L\"\nlong_action = \"check\"\n")
                .rfind("b.toml:4:15: button[0].long_action: unknown key (expected one of name, line,", 0),
            0u);
  EXPECT_EQ(error_of("[[led]]\nname = \"a\"\nline = \"L\"\npattern = \"blink\"\n"),
            "b.toml:4:11: led[0].pattern: unknown key (expected one of name, line, chip, offset, active_low, bias)");
  EXPECT_EQ(error_of("[camera]\ndevice = \"/dev/video0\"\nfps = 30\n").rfind("b.toml:3:7: camera.fps: unknown key (", 0), 0u);
  EXPECT_EQ(error_of("[mock]\nimages = []\n"),
            "b.toml:2:10: mock.images: unknown key (expected one of button_script, camera_images)");
}

// The kernel grants a GPIO line to one request: a line named by a button and an LED, or by two of
// either, is refused where it is named the second time.
TEST(Board, RefusesAGpioLineUsedTwice) {
  EXPECT_EQ(error_of("[[button]]\nname = \"play\"\nline = \"GPIO17\"\n[[led]]\nname = \"status\"\nline = \"GPIO17\"\n"),
            "b.toml:6:8: led[0].line: expected a GPIO line no other button or LED uses (button 'play' uses line GPIO17), got "
            "'GPIO17'");
  EXPECT_EQ(
      error_of("[[button]]\nname = \"a\"\nchip = \"gpiochip0\"\noffset = 4\n"
               "[[button]]\nname = \"b\"\nchip = \"gpiochip0\"\noffset = 4\n"),
      "b.toml:8:10: button[1].offset: expected a GPIO line no other button or LED uses (button 'a' uses gpiochip0:4), got 4");
  EXPECT_EQ(error_of("[[led]]\nname = \"a\"\nline = \"L\"\n[[led]]\nname = \"b\"\nline = \"L\"\n"),
            "b.toml:6:8: led[1].line: expected a GPIO line no other button or LED uses (LED 'a' uses line L), got 'L'");
  // The same offset on another chip, and different names, are different lines.
  EXPECT_EQ(error_of("[[button]]\nname = \"a\"\nchip = \"gpiochip0\"\noffset = 4\n"
                     "[[led]]\nname = \"b\"\nchip = \"gpiochip1\"\noffset = 4\n"
                     "[[led]]\nname = \"c\"\nline = \"GPIO4\"\n"),
            "no error");
}

// Found by tests/fuzz (regressions/board/float_beyond_long.toml): a float where an integer belongs
// went through toml++'s unchecked float-to-integer conversion.
TEST(Board, AFloatBeyondAnyIntegerIsRefusedAsNotAnInteger) {
  EXPECT_EQ(error_of("[camera]\ndevice = \"/dev/video0\"\nwidth = 1e280\n"),
            "b.toml:3:9: camera.width: expected an integer in 16..8192, got 1e+280");
  EXPECT_EQ(error_of("[camera]\ndevice = \"/dev/video0\"\nheight = 720.0\n"),
            "b.toml:3:10: camera.height: expected an integer in 16..8192, got 720.0");
  const std::string file = std::string(HAL_SOURCE_DIR) + "/tests/fuzz/regressions/board/float_beyond_long.toml";
  try {
    load_board(file);
    ADD_FAILURE() << file << " loaded";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), file + ":3:9: camera.width: expected an integer in 16..8192, got 1e+280");
  }
}

TEST(Board, ShippedBoardFilesParse) {
  for (const char* f : {"raspberry-pi-4.toml", "raspberry-pi-5.toml", "mock.toml"}) {
    SCOPED_TRACE(f);
    const BoardConfig b = load_board(std::string(HAL_SOURCE_DIR) + "/board/" + f);
    EXPECT_FALSE(b.buttons.empty());
    EXPECT_FALSE(b.leds.empty());
    EXPECT_TRUE(b.camera.has_value());
    // The boards a service runs on listen for `player ctl` where the unit's RuntimeDirectory is.
    EXPECT_EQ(b.control, std::string(f) == "mock.toml" ? "" : "/run/ssao-player/control");
    EXPECT_EQ(b.metrics_file, std::string(f) == "mock.toml" ? "" : "/run/ssao-player/ssao-player.prom");
  }
  EXPECT_EQ(builtin_mock_board().control, "") << "no socket unless a board file or --control asks for one";
}

}  // namespace
}  // namespace hal
