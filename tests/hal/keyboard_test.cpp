// Keyboards as buttons on the linux backend: key names everywhere; real keyboards (uinput) where the
// kernel has uinput and we are root, which the vm tier provides.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <libevdev/libevdev-uinput.h>
#include <libevdev/libevdev.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include "button_events.h"
#include "gpio_devices.h"
#include "hal/devices.h"
#include "keyboards_evdev.h"

namespace hal {
namespace {

using test::describe;
using test::wait_events;

namespace fs = std::filesystem;
using std::chrono::milliseconds;
using std::chrono::seconds;

TEST(KeyNames, EvdevKeysHaveTheWindowPlatformsNames) {
  // The board defaults' keys, then keys whose evdev and SDL names differ (the window platform writes
  // SDL's names in lower case, '-' for ' ').
  const std::map<unsigned, std::string> expected = {
      {KEY_SPACE, "space"},
      {KEY_N, "n"},
      {KEY_P, "p"},
      {KEY_C, "c"},
      {KEY_RIGHT, "right"},
      {KEY_F11, "f11"},
      {KEY_1, "1"},
      {KEY_PAGEDOWN, "pagedown"},
      {KEY_ENTER, "return"},
      {KEY_ESC, "escape"},
      {KEY_LEFTCTRL, "left-ctrl"},
      {KEY_RIGHTMETA, "right-gui"},
      {KEY_KP1, "keypad-1"},
      {KEY_KPENTER, "keypad-enter"},
      {KEY_MINUS, "-"},
      {KEY_PLAYPAUSE, "audioplay"},
      {KEY_NEXTSONG, "audionext"},
  };
  for (const auto& [code, name] : expected) EXPECT_EQ(detail::board_key_name(code), name) << "code " << code;
}

TEST(KeyNames, MouseAndJoystickButtonsAreNoKeys) {
  for (unsigned code : {unsigned{BTN_LEFT}, unsigned{BTN_SOUTH}, unsigned{BTN_TOUCH}, unsigned{KEY_RESERVED}, unsigned{KEY_MAX}})
    EXPECT_EQ(detail::board_key_name(code), "") << "code " << code;
}

// A board's `key` must name one key: two codes with one name would make the button answer to the
// wrong one too.
TEST(KeyNames, EveryNameIsOneKey) {
  std::map<std::string, unsigned> seen;
  for (unsigned code = 0; code <= KEY_MAX; ++code) {
    const std::string name = detail::board_key_name(code);
    if (name.empty()) continue;
    const auto [it, inserted] = seen.emplace(name, code);
    EXPECT_TRUE(inserted) << "'" << name << "' names codes " << it->second << " and " << code;
  }
  EXPECT_GT(seen.size(), 100u);
}

class NoKeys final : public detail::KeySink {
 public:
  std::size_t calls = 0;
  void key(std::size_t, bool, Nanos) override { ++calls; }
};

bool readable(int fd) {
  pollfd p{fd, POLLIN, 0};
  return poll(&p, 1, 0) == 1;
}

TEST(Keyboards, NoButtonWithAKeyWatchesNothing) {
  MonotonicClock clock;
  detail::Keyboards k({"", ""}, "/dev/input", clock);
  EXPECT_FALSE(k.active());
  EXPECT_EQ(k.open_count(), 0u);
}

// A board that boots without any input device has no /dev/input: the folder is watched for once it
// appears, files in it that are not input devices are passed over, and the fd goes quiet once read
// (so the app's poll loop does not spin).
TEST(Keyboards, InputFolderAppearingLaterIsWatchedAndNonDevicesIgnored) {
  const fs::path dir = fs::path(HAL_TEST_OUTPUT_DIR) / "keyboards";
  fs::remove_all(dir);
  fs::create_directories(dir);
  MonotonicClock clock;
  detail::Keyboards k({"space", "n"}, (dir / "input").string(), clock);
  ASSERT_TRUE(k.active());
  NoKeys sink;
  k.read(sink);
  EXPECT_FALSE(readable(k.fd()));
  fs::create_directory(dir / "input");
  EXPECT_TRUE(readable(k.fd()));
  k.read(sink);
  EXPECT_FALSE(readable(k.fd()));
  std::ofstream(dir / "input" / "event0") << "not a device";
  EXPECT_TRUE(readable(k.fd()));
  k.read(sink);
  EXPECT_FALSE(readable(k.fd()));
  EXPECT_EQ(k.open_count(), 0u);
  EXPECT_EQ(sink.calls, 0u);
}

// ---- Hardware tier: keyboards made with uinput (the vm tier runs these) ----

std::string uinput_skip_reason() {
  if (!fs::exists("/dev/uinput")) return "no /dev/uinput (modprobe uinput; the vm tier runs this)";
  if (geteuid() != 0) return "/dev/uinput present but creating a keyboard needs root";
  return "";
}

// A virtual USB keyboard: appears in /dev/input when made, disappears when unplugged.
class VirtualKeyboard {
 public:
  ~VirtualKeyboard() {
    unplug();
    if (dev_) libevdev_free(dev_);
  }
  std::string plug_in(const char* name) {
    dev_ = libevdev_new();
    libevdev_set_name(dev_, name);
    libevdev_set_id_bustype(dev_, BUS_USB);
    libevdev_enable_event_type(dev_, EV_KEY);
    for (unsigned code = KEY_ESC; code <= KEY_KPDOT; ++code) libevdev_enable_event_code(dev_, EV_KEY, code, nullptr);
    const int rc = libevdev_uinput_create_from_device(dev_, LIBEVDEV_UINPUT_OPEN_MANAGED, &ui_);
    if (rc < 0) {
      ui_ = nullptr;
      return std::string("uinput: cannot create '") + name + "': " + std::strerror(-rc);
    }
    return "";
  }
  // value 1 press, 0 release, 2 the keyboard's auto-repeat.
  void key(unsigned code, int value) {
    libevdev_uinput_write_event(ui_, EV_KEY, code, value);
    libevdev_uinput_write_event(ui_, EV_SYN, SYN_REPORT, 0);
  }
  void unplug() {
    if (ui_) libevdev_uinput_destroy(ui_);
    ui_ = nullptr;
  }

 private:
  libevdev* dev_ = nullptr;
  libevdev_uinput* ui_ = nullptr;
};

// Runs the buttons' read loop until `n` keyboards are open (a keyboard is only heard once open).
bool wait_keyboards(detail::EdgeButtons& b, std::size_t n) {
  const auto end = std::chrono::steady_clock::now() + seconds(10);
  while (b.keyboards_open() != n && std::chrono::steady_clock::now() < end) {
    pollfd p{b.fd(), POLLIN, 0};
    poll(&p, 1, 50);
    std::array<ButtonEvent, 8> ev;
    EXPECT_EQ(b.read(ev), 0u) << "an event while waiting for a keyboard";
  }
  return b.keyboards_open() == n;
}

const char* const kKeyboardBoard = R"(
[buttons]
debounce_ms = 10
[[button]]
name = "play"                 # key "space" by default
line = "VM_KBD_NO_PLAY_LINE"
[[button]]
name = "next"                 # key "n" by default
line = "VM_KBD_NO_NEXT_LINE"
long_press_ms = 0
)";

// Keys act as the buttons whose `key` they are, through open_devices and the linux backend, from a
// keyboard there at start and from one plugged in later; unplugging one (even with a key down)
// leaves the buttons working and none held.
// Keyboards the machine has already (QEMU's PS/2 keyboard in the vm tier) with the board's keys.
std::size_t keyboards_present(const char* board) {
  MonotonicClock clock;
  Devices d = open_devices(parse_board(board, "keyboard-board.toml"), Backend::linux_kernel, clock);
  return dynamic_cast<detail::EdgeButtons&>(*d.buttons).keyboards_open();
}

TEST(Hardware, UinputKeyboardPressesTheButtonOfItsKey) {
  if (const std::string why = uinput_skip_reason(); !why.empty()) GTEST_SKIP() << why;
  const std::size_t present = keyboards_present(kKeyboardBoard);
  VirtualKeyboard first;
  ASSERT_EQ(first.plug_in("hal-test keyboard 1"), "");
  MonotonicClock clock;
  Devices d = open_devices(parse_board(kKeyboardBoard, "keyboard-board.toml"), Backend::linux_kernel, clock);
  // The lines are missing (reported), the keys still work.
  ASSERT_EQ(d.problems.size(), 2u) << d.problems[0];
  auto* b = dynamic_cast<detail::EdgeButtons*>(d.buttons.get());
  ASSERT_NE(b, nullptr);
  ASSERT_TRUE(wait_keyboards(*b, present + 1)) << b->keyboards_open() << " keyboards open, " << present << " before";

  // A click of n: press, then release once the press is through the debounce. The keyboard's own
  // auto-repeat (value 2) is not a press.
  first.key(KEY_N, 1);
  first.key(KEY_N, 2);
  std::vector<ButtonEvent> ev = wait_events(*b, 1);
  first.key(KEY_N, 2);
  first.key(KEY_N, 0);
  const std::vector<ButtonEvent> rest = wait_events(*b, 1);
  ev.insert(ev.end(), rest.begin(), rest.end());
  ASSERT_EQ(ev.size(), 2u) << describe(ev, *b);
  EXPECT_EQ(b->name(ev[0].button), "next");
  EXPECT_EQ(ev[0].action, ButtonAction::press);
  EXPECT_EQ(ev[1].button, ev[0].button);
  EXPECT_EQ(ev[1].action, ButtonAction::release);
  // Kernel timestamps on hal's clock (CLOCK_MONOTONIC), not the wall clock's decades away.
  EXPECT_LT(ev[1].time, clock.now());
  EXPECT_GT(ev[0].time, clock.now() - seconds(60));

  // A key no button has changes nothing.
  first.key(KEY_A, 1);
  first.key(KEY_A, 0);

  // Plugged in while running.
  VirtualKeyboard second;
  ASSERT_EQ(second.plug_in("hal-test keyboard 2"), "");
  ASSERT_TRUE(wait_keyboards(*b, present + 2)) << b->keyboards_open() << " keyboards open";
  second.key(KEY_SPACE, 1);
  ev = wait_events(*b, 1);
  ASSERT_EQ(ev.size(), 1u) << describe(ev, *b);
  EXPECT_EQ(b->name(ev[0].button), "play");
  EXPECT_EQ(ev[0].action, ButtonAction::press);

  // The first one unplugged: the second, holding space, goes on; then it is pulled out with space
  // still down, which lets play go.
  first.unplug();
  ASSERT_TRUE(wait_keyboards(*b, present + 1));
  second.unplug();
  ev = wait_events(*b, 1);
  ASSERT_EQ(ev.size(), 1u) << describe(ev, *b);
  EXPECT_EQ(b->name(ev[0].button), "play");
  EXPECT_EQ(ev[0].action, ButtonAction::release);
  EXPECT_EQ(b->keyboards_open(), present);
  EXPECT_EQ(b->last_error(), "") << "an unplugged keyboard is no failure";
  std::array<ButtonEvent, 4> none;
  EXPECT_EQ(b->read(none), 0u);
  EXPECT_FALSE(readable(b->fd())) << "the buttons' fd stays readable: the app's loop would spin";
}

// A button on a GPIO line with a key too: down while either holds it, one press and one release.
TEST(Hardware, KeyAndLineHoldOneButtonTogether) {
  if (const std::string why = uinput_skip_reason(); !why.empty()) GTEST_SKIP() << why;
  if (!fs::exists("/sys/kernel/config/gpio-sim")) GTEST_SKIP() << "gpio-sim not available (the vm tier runs this)";
  // A gpio-sim chip with one named line, as in linux_test.cpp.
  const fs::path sim = fs::path("/sys/kernel/config/gpio-sim") / ("hal-kbd-" + std::to_string(getpid()));
  auto put = [](const fs::path& p, const std::string& v) {
    std::ofstream out(p);
    out << v;
    out.close();
    return !out.fail();
  };
  fs::create_directories(sim / "bank0" / "line0");
  struct Cleanup {
    fs::path sim;
    ~Cleanup() {
      std::ofstream(sim / "live") << "0";
      std::error_code ec;
      fs::remove(sim / "bank0" / "line0", ec);
      fs::remove(sim / "bank0", ec);
      fs::remove(sim, ec);
    }
  } cleanup{sim};
  ASSERT_TRUE(put(sim / "bank0" / "num_lines", "1"));
  ASSERT_TRUE(put(sim / "bank0" / "line0" / "name", "VM_KBD_NEXT"));
  ASSERT_TRUE(put(sim / "live", "1"));
  auto attr = [&](const char* file) {
    std::string dev, chip;
    std::ifstream(sim / "dev_name") >> dev;
    std::ifstream(sim / "bank0" / "chip_name") >> chip;
    return fs::path("/sys/devices/platform") / dev / chip / "sim_gpio0" / file;
  };

  const char* const board = R"(
[[button]]
name = "next"
line = "VM_KBD_NEXT"
bias = "pull-down"
debounce_ms = 10
long_press_ms = 0
)";
  const std::size_t present = keyboards_present(board);
  VirtualKeyboard keyboard;
  ASSERT_EQ(keyboard.plug_in("hal-test keyboard"), "");
  MonotonicClock clock;
  Devices d = open_devices(parse_board(board, "key-and-line.toml"), Backend::linux_kernel, clock);
  ASSERT_TRUE(d.problems.empty()) << d.problems[0];
  auto* b = dynamic_cast<detail::EdgeButtons*>(d.buttons.get());
  ASSERT_NE(b, nullptr);
  ASSERT_TRUE(wait_keyboards(*b, present + 1));

  ASSERT_TRUE(put(attr("pull"), "pull-up"));  // the line pressed
  std::vector<ButtonEvent> ev = wait_events(*b, 1);
  ASSERT_EQ(ev.size(), 1u) << describe(ev, *b);
  EXPECT_EQ(ev[0].action, ButtonAction::press);
  keyboard.key(KEY_N, 1);  // the key too; read before the line moves, as a person's hands would
  pollfd p{b->fd(), POLLIN, 0};
  ASSERT_EQ(poll(&p, 1, 10'000), 1) << "the key press never reached the buttons' fd";
  std::array<ButtonEvent, 4> none;
  EXPECT_EQ(b->read(none), 0u);
  // Read until the fd stays quiet: a debounce deadline can make it readable before the key's event
  // has reached the keyboard's node (seen under TCG), and the press must be in before the line moves.
  while (poll(&p, 1, 200) == 1) EXPECT_EQ(b->read(none), 0u);
  ASSERT_TRUE(put(attr("pull"), "pull-down"));  // the line let go: the key still holds it
  // Nothing, however long after the line's edge and its debounce, while the key is held.
  while (poll(&p, 1, 300) == 1) ASSERT_EQ(b->read(none), 0u) << "released with the line, while the key still held the button";
  const Nanos line_released = clock.now();
  keyboard.key(KEY_N, 0);
  ev = wait_events(*b, 1);
  ASSERT_EQ(ev.size(), 1u) << describe(ev, *b);
  EXPECT_EQ(ev[0].action, ButtonAction::release);
  EXPECT_GE(ev[0].time, line_released) << "released before the key let go";
  EXPECT_EQ(b->read(none), 0u);
}

}  // namespace
}  // namespace hal
