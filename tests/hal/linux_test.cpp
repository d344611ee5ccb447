// Linux backends: error paths everywhere; real devices only where the kernel's simulators exist.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <linux/gpio.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "button_events.h"
#include "camera_schedule.h"
#include "colour_bars.h"
#include "gpio_devices.h"
#include "hal/devices.h"
#include "hal/mock.h"

namespace hal {
namespace {

using test::describe;
using test::wait_events;

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
  EXPECT_EQ(problems[0].rfind("button 'play': GPIO chip 'gpiochip-does-not-exist' for gpiochip-does-not-exist:3: cannot open", 0),
            0u)
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
  status.set_pattern(0, LedPattern::blink_fast);
  status.set_pattern(1, LedPattern::on);
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
  EXPECT_EQ(ev[0].action, ButtonAction::press);
  EXPECT_EQ(ev[0].time, milliseconds(900));
  EXPECT_EQ(b.last_error(), "button 'play': GPIO line GPIO17: reading edge events: Input/output error; button disabled");
  clock.advance(milliseconds(100));
  ASSERT_EQ(b.read(ev), 1u);
  EXPECT_EQ(ev[0].action, ButtonAction::release);
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
  status.set_pattern(0, LedPattern::blink_fast);
  status.set_pattern(1, LedPattern::blink_fast);
  EXPECT_TRUE(status.led_error().empty());
  leds.chip_gone = true;
  leds.writes.clear();
  for (int i = 0; i < 5; ++i) {
    clock.advance(milliseconds(100));
    status.update();
  }
  EXPECT_EQ(status.led_error(), "LED 'error' (GPIO line GPIO24): set value: No such device (chip removed?); LED disabled");
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
  EXPECT_EQ(cam->state(), CameraState::lost);
  EXPECT_EQ(cam->last_error(), cfg.device + ": cannot open camera: No such file or directory");
  std::ofstream(cfg.device) << "not a camera";  // the device appears, as when it is plugged back in
  clock.advance(milliseconds(4999));
  cam->service();
  EXPECT_EQ(cam->last_error(), cfg.device + ": cannot open camera: No such file or directory") << "reopened early";
  clock.advance(milliseconds(1));
  cam->service();
  EXPECT_EQ(cam->state(), CameraState::lost);
  EXPECT_NE(cam->last_error().find("VIDIOC_QUERYCAP failed (not a V4L2 device?)"), std::string::npos) << cam->last_error();
}

TEST(LinuxCamera, MissingDeviceIsLostNamedAndRetried) {
  CameraConfig cfg;
  cfg.device = "/dev/v4l/by-id/usb-no-such-camera-video-index0";
  cfg.reopen_interval = std::chrono::milliseconds(100);
  MonotonicClock clock;
  auto cam = open_v4l2_camera(cfg, clock);
  EXPECT_EQ(cam->state(), CameraState::lost);
  EXPECT_EQ(cam->last_error(), cfg.device + ": cannot open camera: No such file or directory");
  RgbImage f;
  EXPECT_FALSE(cam->read_frame(f));
  // capture() waits for the reopen timer, retries, and gives up at its timeout without hanging.
  EXPECT_FALSE(cam->capture(f, std::chrono::milliseconds(250)));
  EXPECT_EQ(cam->state(), CameraState::lost);
  EXPECT_NE(cam->last_error().find("No such file or directory"), std::string::npos);
}

TEST(LinuxCamera, NonV4l2DeviceIsRejectedWithTheReason) {
  CameraConfig cfg;
  cfg.device = "/dev/null";
  MonotonicClock clock;
  auto cam = open_v4l2_camera(cfg, clock);
  EXPECT_EQ(cam->state(), CameraState::lost);
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
)",
                                        "degraded.toml");
  MonotonicClock clock;
  Devices d = open_devices(board, Backend::linux_kernel, clock);
  EXPECT_EQ(d.problems.size(), 3u);
  ASSERT_TRUE(d.buttons && d.status && d.camera);
  d.status->set_pattern(0, LedPattern::blink_fast);
  d.status->update();
  EXPECT_EQ(d.camera->state(), CameraState::lost);
}

// Hardware tier: the kernel's simulators (gpio-sim, vivid). Creating gpio-sim chips needs configfs
// and root, unbinding vivid needs root; CI containers have neither driver, so these skip there and
// run in the vm tier (tests/vm: a QEMU guest whose kernel has both built in).
namespace fs = std::filesystem;
using std::chrono::seconds;

std::string read_attr(const fs::path& p) {
  std::ifstream in(p);
  std::string v;
  std::getline(in, v);
  return v;
}

// Writes a sysfs or configfs attribute in one write(2), as the kernel wants it; "" or the error.
std::string write_attr(const fs::path& p, const std::string& v) {
  const int fd = ::open(p.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) return p.string() + ": open: " + std::strerror(errno);
  const ssize_t n = ::write(fd, v.data(), v.size());
  const int err = errno;
  ::close(fd);
  if (n != static_cast<ssize_t>(v.size())) return p.string() + ": write '" + v + "': " + std::strerror(err);
  return "";
}

std::string gpio_sim_skip_reason() {
  if (!fs::exists("/sys/kernel/config/gpio-sim"))
    return "gpio-sim not available (/sys/kernel/config/gpio-sim missing: modprobe gpio-sim, mount configfs; "
           "the vm tier runs this)";
  if (geteuid() != 0) return "gpio-sim present but creating a chip needs root";
  return "";
}

// A gpio-sim chip with named lines, made through configfs for one test and removed with it.
class GpioSim {
 public:
  ~GpioSim() { remove(); }
  // "" when the chip is live, else what failed.
  std::string make(const std::vector<std::string>& line_names) {
    static int serial = 0;
    dir_ = fs::path("/sys/kernel/config/gpio-sim") / ("hal-test-" + std::to_string(getpid()) + "-" + std::to_string(serial++));
    std::error_code ec;
    fs::create_directories(dir_ / "bank0", ec);
    if (ec) return dir_.string() + ": " + ec.message();
    lines_ = line_names.size();
    if (auto e = write_attr(dir_ / "bank0" / "num_lines", std::to_string(lines_)); !e.empty()) return e;
    for (std::size_t i = 0; i < lines_; ++i) {
      if (line_names[i].empty()) continue;  // an unnamed line needs no folder
      const fs::path line = dir_ / "bank0" / ("line" + std::to_string(i));
      fs::create_directory(line, ec);
      if (ec) return line.string() + ": " + ec.message();
      if (auto e = write_attr(line / "name", line_names[i]); !e.empty()) return e;
    }
    if (auto e = write_attr(dir_ / "live", "1"); !e.empty()) return e;
    live_ = true;
    chip_ = read_attr(dir_ / "bank0" / "chip_name");
    dev_name_ = read_attr(dir_ / "dev_name");
    if (chip_.empty() || dev_name_.empty()) return dir_.string() + ": no chip_name or dev_name after going live";
    return "";
  }
  const std::string& chip() const { return chip_; }
  // The simulated line's sysfs attribute: `pull` drives an input from outside, `value` shows the level.
  fs::path attr(std::size_t offset, const char* name) const {
    return fs::path("/sys/devices/platform") / dev_name_ / chip_ / ("sim_gpio" + std::to_string(offset)) / name;
  }

 private:
  void remove() {
    if (dir_.empty()) return;
    if (live_) write_attr(dir_ / "live", "0");
    std::error_code ec;
    for (std::size_t i = 0; i < lines_; ++i) fs::remove(dir_ / "bank0" / ("line" + std::to_string(i)), ec);
    fs::remove(dir_ / "bank0", ec);
    fs::remove(dir_, ec);
  }
  fs::path dir_;
  std::size_t lines_ = 0;
  bool live_ = false;
  std::string chip_, dev_name_;
};

TEST(Hardware, GpioSimButtons) {
  if (const std::string why = gpio_sim_skip_reason(); !why.empty()) GTEST_SKIP() << why;
  GpioSim sim;
  ASSERT_EQ(sim.make({"HAL_TEST_BTN", "", "", ""}), "");
  MonotonicClock clock;
  std::vector<std::string> problems;
  std::vector<ButtonConfig> cfg(1);
  cfg[0].name = "btn";
  cfg[0].line.line_name = "HAL_TEST_BTN";
  cfg[0].timing.debounce = std::chrono::milliseconds(5);
  auto buttons = open_gpio_buttons(cfg, "hal-test", clock, problems);
  EXPECT_TRUE(problems.empty()) << (problems.empty() ? "" : problems[0]);
  // Drive the simulated line high through sysfs: a press once the debounce has passed.
  ASSERT_EQ(write_attr(sim.attr(0, "pull"), "pull-up"), "");
  const std::vector<ButtonEvent> ev = wait_events(*buttons, 1);
  ASSERT_EQ(ev.size(), 1u) << describe(ev, *buttons);
  EXPECT_EQ(ev[0].action, ButtonAction::press);
}

// A board file's buttons and LEDs on real GPIO lines: open_devices with the linux backend finds the
// lines by name, the kernel applies bias and active-low, edges become debounced presses, releases
// and long presses, and the LED patterns reach the lines.
TEST(Hardware, GpioSimBoardButtonsAndLeds) {
  if (const std::string why = gpio_sim_skip_reason(); !why.empty()) GTEST_SKIP() << why;
  GpioSim sim;
  ASSERT_EQ(sim.make({"VM_BTN_PLAY", "VM_BTN_NEXT", "VM_LED_STATUS", "VM_LED_ERROR"}), "");
  const BoardConfig board = parse_board(R"(
[board]
consumer = "hal-vm-test"
[buttons]
debounce_ms = 10
long_press_ms = 300
[[button]]
name = "play"
line = "VM_BTN_PLAY"
active_low = true       # pressed = pulled to ground, as board/raspberry-pi-4.toml wires it
bias = "pull-up"
[[button]]
name = "next"
line = "VM_BTN_NEXT"
bias = "pull-down"
long_press_ms = 0
[[led]]
name = "status"
line = "VM_LED_STATUS"
[[led]]
name = "error"
line = "VM_LED_ERROR"
active_low = true
)",
                                        "gpio-sim-board.toml");
  MonotonicClock clock;
  Devices d = open_devices(board, Backend::linux_kernel, clock);
  ASSERT_TRUE(d.problems.empty()) << d.problems[0];
  Buttons& b = *d.buttons;
  ASSERT_EQ(b.count(), 2u);

  // The requested bias reaches the simulator, which pulls the idle lines accordingly: nothing held.
  EXPECT_EQ(read_attr(sim.attr(0, "pull")), "pull-up");
  EXPECT_EQ(read_attr(sim.attr(1, "pull")), "pull-down");
  std::array<ButtonEvent, 4> none;
  EXPECT_EQ(b.read(none), 0u);

  // play: active low, so pulling the line down presses it; held past long_press_ms, a long press
  // stamped exactly long_press_ms after the press; let go, a release.
  ASSERT_EQ(write_attr(sim.attr(0, "pull"), "pull-down"), "");
  std::vector<ButtonEvent> ev = wait_events(b, 2);
  ASSERT_EQ(ev.size(), 2u) << describe(ev, b);
  EXPECT_EQ(ev[0].button, 0);
  EXPECT_EQ(ev[0].action, ButtonAction::press);
  EXPECT_EQ(ev[1].action, ButtonAction::long_press);
  EXPECT_EQ(ev[1].time - ev[0].time, std::chrono::milliseconds(300));
  ASSERT_EQ(write_attr(sim.attr(0, "pull"), "pull-up"), "");
  ev = wait_events(b, 1);
  ASSERT_EQ(ev.size(), 1u) << describe(ev, b);
  EXPECT_EQ(ev[0].button, 0);
  EXPECT_EQ(ev[0].action, ButtonAction::release);

  // next: active high with a pull-down; a click, and no long press (long_press_ms = 0).
  ASSERT_EQ(write_attr(sim.attr(1, "pull"), "pull-up"), "");
  ev = wait_events(b, 1);
  ASSERT_EQ(write_attr(sim.attr(1, "pull"), "pull-down"), "");
  const std::vector<ButtonEvent> rest = wait_events(b, 1);
  ev.insert(ev.end(), rest.begin(), rest.end());
  ASSERT_EQ(ev.size(), 2u) << describe(ev, b);
  EXPECT_EQ(ev[0].button, 1);
  EXPECT_EQ(ev[0].action, ButtonAction::press);
  EXPECT_EQ(ev[1].button, 1);
  EXPECT_EQ(ev[1].action, ButtonAction::release);
  EXPECT_LT(ev[0].time, ev[1].time);
  EXPECT_EQ(b.read(none), 0u);
  EXPECT_EQ(b.last_error(), "");

  // LEDs: the simulator's `value` is the physical level, so the active-low LED reads inverted.
  Status& st = *d.status;
  ASSERT_EQ(st.led_count(), 2u);
  const fs::path status_value = sim.attr(2, "value"), error_value = sim.attr(3, "value");
  st.set_pattern(0, LedPattern::on);
  st.set_pattern(1, LedPattern::on);
  st.update();
  EXPECT_EQ(read_attr(status_value), "1");
  EXPECT_EQ(read_attr(error_value), "0");
  st.set_pattern(0, LedPattern::off);
  st.set_pattern(1, LedPattern::off);
  st.update();
  EXPECT_EQ(read_attr(status_value), "0");
  EXPECT_EQ(read_attr(error_value), "1");
  // A blink: each time the status timer fires, the line follows the pattern's level; four changes
  // are seen (at least two full on/off cycles).
  st.set_pattern(0, LedPattern::blink_fast);
  st.update();
  EXPECT_EQ(read_attr(status_value), st.level(0) ? "1" : "0");
  int changes = 0;
  bool last = st.level(0);
  const auto end = std::chrono::steady_clock::now() + seconds(10);
  while (changes < 4 && std::chrono::steady_clock::now() < end) {
    pollfd p{st.fd(), POLLIN, 0};
    poll(&p, 1, 100);
    st.update();
    ASSERT_EQ(read_attr(status_value), st.level(0) ? "1" : "0") << "after " << changes << " changes";
    if (st.level(0) != last) {
      ++changes;
      last = st.level(0);
    }
  }
  EXPECT_EQ(changes, 4) << "the blinking LED line stopped changing";
  EXPECT_EQ(read_attr(error_value), "1") << "the other LED moved";
  EXPECT_EQ(st.led_error(), "");
}

// The first vivid video capture node, e.g. "video0" (vivid also makes output, VBI, SDR and metadata
// nodes), or "".
std::string vivid_capture_node() {
  for (int i = 0; i < 64; ++i) {
    const std::string node = "video" + std::to_string(i);
    const std::string name = read_attr("/sys/class/video4linux/" + node + "/name");
    if (name.find("vivid") != std::string::npos && name.find("vid-cap") != std::string::npos) return node;
  }
  return "";
}

TEST(Hardware, VividCapture) {
  const std::string node = vivid_capture_node();
  if (node.empty()) GTEST_SKIP() << "no vivid device (modprobe vivid; the vm tier runs this) and no /dev/video* from it";
  const std::string device = "/dev/" + node;
  for (PixelFormat f : {PixelFormat::yuyv, PixelFormat::rgb24}) {
    CameraConfig cfg;
    cfg.device = device;
    cfg.width = 640;
    cfg.height = 480;
    cfg.format = f;
    MonotonicClock clock;
    auto cam = open_v4l2_camera(cfg, clock);
    ASSERT_EQ(cam->state(), CameraState::streaming) << cam->last_error();
    RgbImage frame;
    ASSERT_TRUE(cam->capture(frame, std::chrono::seconds(5))) << cam->last_error();
    EXPECT_EQ(frame.width, 640);
    EXPECT_EQ(frame.height, 480);
    // vivid's default pattern, 75% colour bars (colour_bars.h). Tolerance 8 of 255: YUYV is 8-bit
    // limited range, and vivid computes its Y'CbCr values with its own coefficients and rounding;
    // our conversion of exact BT.601 values is off by at most 1 (ColourBars tests), the rest is
    // margin for vivid's table. RGB24 arrives exact. A wrong bar is off by 64 or more in some
    // channel (75% against 100%), so the margin hides no wrong colour.
    const std::vector<std::string> mismatches = test::colour_bar_mismatches(frame, 8);
    EXPECT_TRUE(mismatches.empty()) << (f == PixelFormat::yuyv ? "YUYV" : "RGB24") << ": " << mismatches.size()
                                    << " bars wrong, first: " << (mismatches.empty() ? "" : mismatches[0]);
  }
}

// Whether this process still holds an fd on `device` (the camera's teardown closes it).
bool holds_fd_on(const std::string& device) {
  for (const auto& e : fs::directory_iterator("/proc/self/fd")) {
    std::error_code ec;
    const std::string target = fs::read_symlink(e.path(), ec).string();
    if (!ec && target.rfind(device, 0) == 0) return true;
  }
  return false;
}

// Runs the camera as the app's loop does (poll its fd, read a frame, service) until `done` holds or
// `guard` passes.
template <class Done>
void pump(Camera& cam, Done done, std::chrono::milliseconds guard = seconds(10)) {
  const auto end = std::chrono::steady_clock::now() + guard;
  RgbImage frame;
  while (!done() && std::chrono::steady_clock::now() < end) {
    pollfd p{cam.fd(), POLLIN, 0};
    poll(&p, 1, 100);
    cam.read_frame(frame);
    if (done()) break;
    cam.service();
  }
}

// Rebinds the vivid device if the test stops while it is unbound, so later tests still have it.
struct Rebind {
  std::string device;
  bool unbound = false;
  ~Rebind() {
    if (unbound) write_attr("/sys/bus/platform/drivers/vivid/bind", device);
  }
};

// The camera unplugged mid-stream and plugged back in, with vivid's platform device unbound from its
// driver and bound again: the camera sees ENODEV, tears down, and reopens by itself one reopen
// interval (on its clock) after the loss, then captures the same pattern again.
TEST(Hardware, VividUnbindAndRebind) {
  const std::string node = vivid_capture_node();
  if (node.empty()) GTEST_SKIP() << "no vivid device (modprobe vivid; the vm tier runs this)";
  if (geteuid() != 0) GTEST_SKIP() << "vivid present but unbinding it needs root";
  const std::string platform_device = fs::canonical("/sys/class/video4linux/" + node + "/device").filename().string();
  const std::string device = "/dev/" + node;
  const BoardConfig board = parse_board(R"([camera]
device = ")" + device + R"("
width = 640
height = 480
format = "yuyv"
reopen_interval_ms = 500
frame_timeout_ms = 5000
)",
                                        "vivid-board.toml");
  // A manual clock decides when the reopen is due, so the test checks the interval exactly; it starts
  // at the real monotonic time so the camera's timerfd deadlines are near, not decades away.
  ManualClock clock(MonotonicClock().now());
  Devices d = open_devices(board, Backend::linux_kernel, clock);
  ASSERT_TRUE(d.problems.empty()) << d.problems[0];
  Camera& cam = *d.camera;
  RgbImage frame;
  ASSERT_TRUE(cam.capture(frame, seconds(10))) << cam.last_error();
  ASSERT_TRUE(holds_fd_on(device));

  Rebind rebind{platform_device};
  ASSERT_EQ(write_attr("/sys/bus/platform/drivers/vivid/unbind", platform_device), "");
  rebind.unbound = true;
  pump(cam, [&] { return cam.state() != CameraState::streaming; });
  ASSERT_EQ(cam.state(), CameraState::lost) << cam.last_error();
  EXPECT_EQ(cam.last_error().rfind(device + ": VIDIOC_DQBUF: No such device (camera unplugged?); retrying", 0), 0u)
      << cam.last_error();
  EXPECT_FALSE(holds_fd_on(device)) << "the lost camera still holds its device open";

  // Unplugged: the try one interval later fails (the node is gone) and schedules the next.
  clock.advance(std::chrono::milliseconds(500));
  cam.service();
  EXPECT_EQ(cam.state(), CameraState::lost);
  EXPECT_EQ(cam.last_error(), device + ": cannot open camera: No such file or directory");

  ASSERT_EQ(write_attr("/sys/bus/platform/drivers/vivid/bind", platform_device), "");
  rebind.unbound = false;
  ASSERT_EQ(vivid_capture_node(), node) << "vivid came back under another node";
  clock.advance(std::chrono::milliseconds(499));
  cam.service();
  EXPECT_EQ(cam.state(), CameraState::lost) << "reopened before its interval";
  clock.advance(std::chrono::milliseconds(1));
  cam.service();
  ASSERT_EQ(cam.state(), CameraState::streaming) << cam.last_error();
  EXPECT_EQ(cam.last_error(), "");
  ASSERT_TRUE(cam.capture(frame, seconds(10))) << cam.last_error();
  EXPECT_EQ(frame.width, 640);
  EXPECT_EQ(frame.height, 480);
  const std::vector<std::string> mismatches = test::colour_bar_mismatches(frame, 8);
  EXPECT_TRUE(mismatches.empty()) << mismatches.size()
                                  << " bars wrong after the rebind, first: " << (mismatches.empty() ? "" : mismatches[0]);
}

}  // namespace
}  // namespace hal
