// Linux backends: error paths everywhere; real devices only where the kernel's simulators exist.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <linux/gpio.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <fstream>

#include "camera_schedule.h"
#include "colour_bars.h"
#include "gpio_devices.h"
#include "hal/devices.h"
#include "hal/mock.h"

namespace hal {
namespace {

using std::chrono::milliseconds;

TEST(LinuxGpio, MissingChipIsNamedAndTheOtherButtonsStillWork) {
  MonotonicClock clock;
  std::vector<std::string> problems;
  std::vector<ButtonConfig> cfg(2);
  cfg[0].name = "play";
  cfg[0].line.chip = "gpiochip-does-not-exist";
  cfg[0].line.offset = 3;
  cfg[1].name = "next";
  cfg[1].line.line_name = "NO_SUCH_LINE_NAME";
  auto buttons = open_gpio_buttons(cfg, "hal-test", clock, problems);
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_EQ(problems[0].rfind("button 'play': GPIO chip 'gpiochip-does-not-exist' for gpiochip-does-not-exist:3: cannot open", 0), 0u)
      << problems[0];
  EXPECT_EQ(problems[1].rfind("button 'next': GPIO line NO_SUCH_LINE_NAME: no chip has a line of that name", 0), 0u)
      << problems[1];
  EXPECT_EQ(buttons->count(), 2u);
  EXPECT_EQ(buttons->name(1), "next");
  std::array<ButtonEvent, 4> ev;
  EXPECT_EQ(buttons->read(ev), 0u);
  EXPECT_GE(buttons->fd(), 0);
}

TEST(LinuxGpio, MissingLedIsNamedAndSettingItIsHarmless) {
  std::vector<std::string> problems;
  std::vector<LedConfig> cfg(2);
  cfg[0].name = "status";
  cfg[0].line.chip = "/dev/gpiochip-missing";
  cfg[0].line.offset = 0;
  cfg[1].name = "error";
  cfg[1].line.line_name = "NO_SUCH_LED_LINE";
  auto leds = open_gpio_leds(cfg, "hal-test", problems);
  ASSERT_EQ(problems.size(), 2u);
  EXPECT_EQ(problems[0].rfind("LED 'status': GPIO chip '/dev/gpiochip-missing' for /dev/gpiochip-missing:0: cannot open", 0), 0u)
      << problems[0];
  EXPECT_EQ(problems[1].rfind("LED 'error': GPIO line NO_SUCH_LED_LINE: no chip has a line of that name", 0), 0u) << problems[1];
  // Harmless: the LEDs were reported once, at start. Setting them (or one past the end) is not a
  // run-time failure, which would log "LED disabled" and light the error LED on every pattern edge.
  for (bool on : {true, false, true}) {
    leds->set(0, on);
    leds->set(1, on);
    leds->set(5, on);
  }
  EXPECT_EQ(leds->last_error(), "");
  // The player drives them through a Status: patterns and levels carry on as if the LEDs were there.
  ManualClock clock;
  Status status({"status", "error"}, std::move(leds), clock, "");
  status.set_pattern(0, LedPattern::BlinkFast);
  status.set_pattern(1, LedPattern::On);
  EXPECT_TRUE(status.level(0));
  clock.advance(milliseconds(100));
  status.update();
  EXPECT_FALSE(status.level(0));
  EXPECT_TRUE(status.level(1));
  EXPECT_EQ(status.led_error(), "");
}

// One LED missing at start, the other present: the missing one is never written (its line was
// never requested), the present one gets every level.
class HalfMissingLeds final : public detail::OutputLeds {
public:
  HalfMissingLeds() : OutputLeds({"LED 'status' (GPIO line GPIO23)", "LED 'error' (GPIO line GPIO24)"}) { disable(0); }
  std::vector<std::pair<std::size_t, bool>> writes;

private:
  int write(std::size_t led, bool on) override {
    writes.push_back({led, on});
    return 0;
  }
};

TEST(LinuxGpio, MissingLedIsNeverWrittenAndTheOthersAre) {
  HalfMissingLeds leds;
  leds.set(0, true);
  leds.set(1, true);
  leds.set(0, false);
  leds.set(1, false);
  leds.set(2, true);
  using Writes = std::vector<std::pair<std::size_t, bool>>;
  EXPECT_EQ(leds.writes, (Writes{{1, true}, {1, false}}));
  EXPECT_EQ(leds.last_error(), "");
}

bool readable(int fd) {
  pollfd p{fd, POLLIN, 0};
  return poll(&p, 1, 0) == 1;
}

// A libgpiod v1 line event fd stands in as a pipe: the kernel's event records written into one end.
// Closing the writer gives what a removed chip gives: a fd that is always ready and fails to read
// (EOF reads as EIO through libgpiod; ENODEV from a real chip takes the same path).
TEST(LinuxGpio, FailedEventFdLeavesThePollSetReleasesTheButtonAndIsReported) {
  ManualClock clock(milliseconds(1000));
  detail::EdgeButtons b({"play"}, {ButtonTiming{milliseconds(20), Nanos{0}, Nanos{0}, milliseconds(100)}}, clock);
  int p[2];
  ASSERT_EQ(pipe(p), 0);
  b.watch(0, p[0], false, "line GPIO17");
  std::array<ButtonEvent, 4> ev;
  EXPECT_EQ(b.read(ev), 0u);
  EXPECT_TRUE(b.last_error().empty());

  gpioevent_data rising{};
  rising.timestamp = static_cast<std::uint64_t>(Nanos(milliseconds(900)).count());
  rising.id = GPIOEVENT_EVENT_RISING_EDGE;
  ASSERT_EQ(write(p[1], &rising, sizeof rising), static_cast<ssize_t>(sizeof rising));
  close(p[1]);
  EXPECT_TRUE(readable(b.fd()));

  // The edge is read, then the fd fails: it leaves the poll set and the held button is let go.
  ASSERT_EQ(b.read(ev), 1u);
  EXPECT_EQ(ev[0].action, ButtonAction::Press);
  EXPECT_EQ(ev[0].time, milliseconds(900));
  EXPECT_EQ(b.last_error(),
            "button 'play': GPIO line GPIO17: reading edge events: Input/output error; button disabled");
  clock.advance(milliseconds(100));
  ASSERT_EQ(b.read(ev), 1u);
  EXPECT_EQ(ev[0].action, ButtonAction::Release);
  EXPECT_EQ(ev[0].time, milliseconds(1000));
  // Nothing due and the dead fd gone: poll() sleeps instead of spinning.
  EXPECT_FALSE(readable(b.fd()));
  EXPECT_EQ(b.read(ev), 0u);
  close(p[0]);
}

// GpioLeds' failure handling with the line write faked: the chip vanishes under LED 1.
class FlakyLeds final : public detail::OutputLeds {
public:
  FlakyLeds() : OutputLeds({"LED 'status' (GPIO line GPIO23)", "LED 'error' (GPIO line GPIO24)"}) {}
  std::vector<std::pair<std::size_t, bool>> writes;
  bool chip_gone = false;

private:
  int write(std::size_t led, bool on) override {
    if (led == 1 && chip_gone) return ENODEV;
    writes.push_back({led, on});
    return 0;
  }
};

TEST(LinuxGpio, FailingLedIsReportedOnceAndTheOthersRunOn) {
  ManualClock clock;
  auto sink = std::make_unique<FlakyLeds>();
  FlakyLeds& leds = *sink;
  Status status({"status", "error"}, std::move(sink), clock, "");
  status.set_pattern(0, LedPattern::BlinkFast);
  status.set_pattern(1, LedPattern::BlinkFast);
  EXPECT_TRUE(status.led_error().empty());
  leds.chip_gone = true;
  leds.writes.clear();
  for (int i = 0; i < 5; ++i) {
    clock.advance(milliseconds(100));
    status.update();
  }
  EXPECT_EQ(status.led_error(),
            "LED 'error' (GPIO line GPIO24): set value: No such device (chip removed?); LED disabled");
  // LED 0 blinked on through every edge; LED 1 was not written again after it failed.
  using Writes = std::vector<std::pair<std::size_t, bool>>;
  EXPECT_EQ(leds.writes, (Writes{{0, false}, {0, true}, {0, false}, {0, true}, {0, false}}));
}

TEST(CameraSchedule, StreamWithoutFramesStallsThenReopensPeriodically) {
  detail::CameraSchedule s(milliseconds(2000), milliseconds(500));
  s.opened(milliseconds(10'000));
  EXPECT_EQ(s.deadline(), milliseconds(10'500));
  s.frame(milliseconds(10'400));
  EXPECT_FALSE(s.stalled(milliseconds(10'899)));
  EXPECT_EQ(s.deadline(), milliseconds(10'900));
  EXPECT_TRUE(s.stalled(milliseconds(10'900)));
  EXPECT_FALSE(s.reopen_due(milliseconds(10'900)));  // streaming: nothing to reopen
  s.lost(milliseconds(10'900));
  EXPECT_FALSE(s.stalled(milliseconds(20'000)));  // lost: no stall to detect
  EXPECT_EQ(s.deadline(), milliseconds(12'900));
  EXPECT_FALSE(s.reopen_due(milliseconds(12'899)));
  EXPECT_TRUE(s.reopen_due(milliseconds(12'900)));
  s.lost(milliseconds(12'900));  // the reopen failed: next try one interval later
  EXPECT_EQ(s.deadline(), milliseconds(14'900));
  s.opened(milliseconds(14'900));
  EXPECT_FALSE(s.stalled(milliseconds(15'399)));
  EXPECT_TRUE(s.stalled(milliseconds(15'400)));
}

// The reopen follows the injected clock, not the monotonic one: a manual clock decides when the
// missing device is tried again, however much real time passes.
TEST(LinuxCamera, ReopenIsTimedByTheInjectedClock) {
  const std::string dir = std::string(HAL_TEST_OUTPUT_DIR) + "/camera_reopen";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  CameraConfig cfg;
  cfg.device = dir + "/video0";
  cfg.reopen_interval = milliseconds(5000);
  ManualClock clock(milliseconds(100'000));
  auto cam = open_v4l2_camera(cfg, clock);
  EXPECT_EQ(cam->state(), CameraState::Lost);
  EXPECT_EQ(cam->last_error(), cfg.device + ": cannot open camera: No such file or directory");
  std::ofstream(cfg.device) << "not a camera";  // the device appears, as when it is plugged back in
  clock.advance(milliseconds(4999));
  cam->service();
  EXPECT_EQ(cam->last_error(), cfg.device + ": cannot open camera: No such file or directory") << "reopened early";
  clock.advance(milliseconds(1));
  cam->service();
  EXPECT_EQ(cam->state(), CameraState::Lost);
  EXPECT_NE(cam->last_error().find("VIDIOC_QUERYCAP failed (not a V4L2 device?)"), std::string::npos)
      << cam->last_error();
}

TEST(LinuxCamera, MissingDeviceIsLostNamedAndRetried) {
  CameraConfig cfg;
  cfg.device = "/dev/v4l/by-id/usb-no-such-camera-video-index0";
  cfg.reopen_interval = std::chrono::milliseconds(100);
  MonotonicClock clock;
  auto cam = open_v4l2_camera(cfg, clock);
  EXPECT_EQ(cam->state(), CameraState::Lost);
  EXPECT_EQ(cam->last_error(), cfg.device + ": cannot open camera: No such file or directory");
  RgbImage f;
  EXPECT_FALSE(cam->read_frame(f));
  // capture() waits for the reopen timer, retries, and gives up at its timeout without hanging.
  EXPECT_FALSE(cam->capture(f, std::chrono::milliseconds(250)));
  EXPECT_EQ(cam->state(), CameraState::Lost);
  EXPECT_NE(cam->last_error().find("No such file or directory"), std::string::npos);
}

TEST(LinuxCamera, NonV4l2DeviceIsRejectedWithTheReason) {
  CameraConfig cfg;
  cfg.device = "/dev/null";
  MonotonicClock clock;
  auto cam = open_v4l2_camera(cfg, clock);
  EXPECT_EQ(cam->state(), CameraState::Lost);
  EXPECT_NE(cam->last_error().find("/dev/null: VIDIOC_QUERYCAP failed (not a V4L2 device?)"), std::string::npos)
      << cam->last_error();
}

TEST(LinuxDevices, BoardWithNothingPresentRunsDegraded) {
  const BoardConfig board = parse_board(R"(
[[button]]
name = "play"
chip = "gpiochip-missing"
offset = 1
[[led]]
name = "status"
line = "MISSING_LED"
[camera]
device = "/dev/video-missing"
)", "degraded.toml");
  MonotonicClock clock;
  Devices d = open_devices(board, Backend::Linux, clock);
  EXPECT_EQ(d.problems.size(), 3u);
  ASSERT_TRUE(d.buttons && d.status && d.camera);
  d.status->set_pattern(0, LedPattern::BlinkFast);
  d.status->update();
  EXPECT_EQ(d.camera->state(), CameraState::Lost);
}

// Hardware tier: the kernel's simulators. Creating gpio-sim chips needs configfs and root, a vivid
// device needs the module loaded; neither exists in CI containers.
TEST(Hardware, GpioSimButtons) {
  if (!std::filesystem::exists("/sys/kernel/config/gpio-sim"))
    GTEST_SKIP() << "gpio-sim not available (/sys/kernel/config/gpio-sim missing: modprobe gpio-sim, mount configfs)";
  if (geteuid() != 0) GTEST_SKIP() << "gpio-sim present but creating a chip needs root";
  namespace fs = std::filesystem;
  const fs::path dev = "/sys/kernel/config/gpio-sim/hal-test";
  fs::create_directories(dev / "bank0");
  auto write = [](const fs::path& p, const std::string& v) {
    FILE* f = std::fopen(p.c_str(), "w");
    ASSERT_NE(f, nullptr) << p;
    std::fputs(v.c_str(), f);
    std::fclose(f);
  };
  write(dev / "bank0" / "num_lines", "4");
  fs::create_directories(dev / "bank0" / "line0");
  write(dev / "bank0" / "line0" / "name", "HAL_TEST_BTN");
  write(dev / "live", "1");
  auto read_attr = [](const fs::path& p) {
    std::string v;
    if (FILE* f = std::fopen(p.c_str(), "r")) {
      char buf[128] = {};
      if (std::fgets(buf, sizeof buf, f)) v = buf;
      std::fclose(f);
    }
    v.erase(v.find_last_not_of('\n') + 1);
    return v;
  };
  const std::string chip = read_attr(dev / "bank0" / "chip_name");
  const std::string platform_dev = read_attr(dev / "dev_name");
  ASSERT_FALSE(chip.empty() || platform_dev.empty());
  MonotonicClock clock;
  std::vector<std::string> problems;
  std::vector<ButtonConfig> cfg(1);
  cfg[0].name = "btn";
  cfg[0].line.line_name = "HAL_TEST_BTN";
  cfg[0].timing.debounce = std::chrono::milliseconds(5);
  auto buttons = open_gpio_buttons(cfg, "hal-test", clock, problems);
  EXPECT_TRUE(problems.empty()) << (problems.empty() ? "" : problems[0]);
  // Drive the simulated line high through sysfs, wait past the debounce, expect a press.
  const fs::path pull = fs::path("/sys/devices/platform") / platform_dev / chip / "sim_gpio0" / "pull";
  ASSERT_TRUE(fs::exists(pull)) << pull;
  write(pull, "pull-up");
  usleep(20000);
  std::array<ButtonEvent, 4> ev;
  const std::size_t n = buttons->read(ev);
  ASSERT_GE(n, 1u);
  EXPECT_EQ(ev[0].action, ButtonAction::Press);
  buttons.reset();
  write(dev / "live", "0");
  fs::remove(dev / "bank0" / "line0");
  fs::remove(dev / "bank0");
  fs::remove(dev);
}

TEST(Hardware, VividCapture) {
  std::string device;
  for (int i = 0; i < 16 && device.empty(); ++i) {
    const std::string name = "/sys/class/video4linux/video" + std::to_string(i) + "/name";
    if (FILE* f = std::fopen(name.c_str(), "r")) {
      char buf[64] = {};
      if (std::fgets(buf, sizeof buf, f) && std::string(buf).find("vivid") != std::string::npos)
        device = "/dev/video" + std::to_string(i);
      std::fclose(f);
    }
  }
  if (device.empty()) GTEST_SKIP() << "no vivid device (modprobe vivid) and no /dev/video* from it";
  for (PixelFormat f : {PixelFormat::Yuyv, PixelFormat::Rgb24}) {
    CameraConfig cfg;
    cfg.device = device;
    cfg.width = 640;
    cfg.height = 480;
    cfg.format = f;
    MonotonicClock clock;
    auto cam = open_v4l2_camera(cfg, clock);
    ASSERT_EQ(cam->state(), CameraState::Streaming) << cam->last_error();
    RgbImage frame;
    ASSERT_TRUE(cam->capture(frame, std::chrono::seconds(2))) << cam->last_error();
    EXPECT_EQ(frame.width, 640);
    EXPECT_EQ(frame.height, 480);
    // vivid's default pattern, 75% colour bars (colour_bars.h). Tolerance 8 of 255: YUYV is 8-bit
    // limited range, and vivid computes its Y'CbCr values with its own coefficients and rounding;
    // our conversion of exact BT.601 values is off by at most 1 (ColourBars tests), the rest is
    // margin for vivid's table. RGB24 arrives exact. A wrong bar is off by 64 or more in some
    // channel (75% against 100%), so the margin hides no wrong colour.
    const std::vector<std::string> mismatches = test::colour_bar_mismatches(frame, 8);
    EXPECT_TRUE(mismatches.empty()) << (f == PixelFormat::Yuyv ? "YUYV" : "RGB24") << ": " << mismatches.size()
                                    << " bars wrong, first: " << (mismatches.empty() ? "" : mismatches[0]);
  }
}

}  // namespace
}  // namespace hal
