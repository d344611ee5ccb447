// Linux backends: error paths everywhere; real devices only where the kernel's simulators exist.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "hal/devices.h"
#include "hal/mock.h"

namespace hal {
namespace {

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
  std::vector<LedConfig> cfg(1);
  cfg[0].name = "status";
  cfg[0].line.chip = "/dev/gpiochip-missing";
  cfg[0].line.offset = 0;
  auto leds = open_gpio_leds(cfg, "hal-test", problems);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("LED 'status': GPIO chip '/dev/gpiochip-missing'"), std::string::npos) << problems[0];
  leds->set(0, true);
  leds->set(5, true);
}

TEST(LinuxCamera, MissingDeviceIsLostNamedAndRetried) {
  CameraConfig cfg;
  cfg.device = "/dev/v4l/by-id/usb-no-such-camera-video-index0";
  cfg.reopen_interval = std::chrono::milliseconds(100);
  auto cam = open_v4l2_camera(cfg);
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
  auto cam = open_v4l2_camera(cfg);
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
    auto cam = open_v4l2_camera(cfg);
    ASSERT_EQ(cam->state(), CameraState::Streaming) << cam->last_error();
    RgbImage frame;
    ASSERT_TRUE(cam->capture(frame, std::chrono::seconds(2))) << cam->last_error();
    EXPECT_EQ(frame.width, 640);
    EXPECT_EQ(frame.height, 480);
  }
}

}  // namespace
}  // namespace hal
