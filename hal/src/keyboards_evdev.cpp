#include "keyboards_evdev.h"

#include <fcntl.h>
#include <libevdev/libevdev.h>
#include <sys/epoll.h>
#include <sys/inotify.h>
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <string_view>
#include <system_error>
#include <utility>

#include "fd.h"

namespace hal::detail {

namespace {

// evdev names (after "KEY_", lower case) whose SDL names differ. The window platform writes SDL's
// names in lower case with '-' for spaces ("Left Ctrl" -> "left-ctrl"), so a board's `key` means the
// same key on a desktop and on a board.
struct Alias {
  std::string_view evdev, board;
};
constexpr Alias kAliases[] = {
    {"enter", "return"},
    {"esc", "escape"},
    {"minus", "-"},
    {"equal", "="},
    {"leftbrace", "["},
    {"rightbrace", "]"},
    {"semicolon", ";"},
    {"apostrophe", "'"},
    {"grave", "`"},
    {"backslash", "\\"},
    {"comma", ","},
    {"dot", "."},
    {"slash", "/"},
    {"leftshift", "left-shift"},
    {"rightshift", "right-shift"},
    {"leftctrl", "left-ctrl"},
    {"rightctrl", "right-ctrl"},
    {"leftalt", "left-alt"},
    {"rightalt", "right-alt"},
    {"leftmeta", "left-gui"},
    {"rightmeta", "right-gui"},
    {"sysrq", "printscreen"},
    {"compose", "application"},
    {"playpause", "audioplay"},
    {"nextsong", "audionext"},
    {"previoussong", "audioprev"},
    {"stopcd", "audiostop"},
    {"kpenter", "keypad-enter"},
    {"kpplus", "keypad-+"},
    {"kpminus", "keypad--"},
    {"kpasterisk", "keypad-*"},
    {"kpslash", "keypad-/"},
    {"kpdot", "keypad-."},
    {"kpequal", "keypad-="},
};

bool starts_with(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

}  // namespace

std::string board_key_name(unsigned code) {
  const char* name = libevdev_event_code_get_name(EV_KEY, code);
  // BTN_* codes are mouse, joystick and remote buttons, not keys; KEY_MAX and the like are no keys.
  if (name == nullptr || !starts_with(name, "KEY_")) return "";
  std::string key(name + 4);
  for (char& c : key) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (key.empty() || key == "reserved" || key == "unknown" || key == "max" || key == "cnt") return "";
  for (const Alias& a : kAliases)
    if (a.evdev == key) return std::string(a.board);
  // KEY_KP0..KEY_KP9 are SDL's "Keypad 0".."Keypad 9".
  if (key.size() == 3 && starts_with(key, "kp") && std::isdigit(static_cast<unsigned char>(key[2])))
    return "keypad-" + key.substr(2);
  return key;
}

struct Keyboards::Device {
  base::UniqueFd fd;
  libevdev* dev = nullptr;
  std::string path;
  dev_t rdev = 0;
  bool monotonic = false;  // event times are CLOCK_MONOTONIC (EVIOCSCLOCKID took)
  std::vector<int> held;   // the mapped codes this keyboard holds down now
  ~Device() {
    if (dev) libevdev_free(dev);
  }
};

Keyboards::Keyboards(const std::vector<std::string>& keys, std::string input_dir, const Clock& clock)
    : button_of_code_(KEY_MAX + 1, -1), input_dir_(std::move(input_dir)), clock_(clock), epoll_(make_epoll()) {
  for (unsigned code = 0; code <= KEY_MAX; ++code) {
    const std::string name = board_key_name(code);
    if (name.empty()) continue;
    for (std::size_t b = 0; b < keys.size(); ++b)
      if (keys[b] == name) {
        button_of_code_[code] = static_cast<int>(b);
        active_ = true;
        break;
      }
  }
  if (!active_) return;
  inotify_.reset(inotify_init1(IN_NONBLOCK | IN_CLOEXEC));
  if (!inotify_) throw std::system_error(errno, std::generic_category(), "inotify_init1");
  epoll_watch(epoll_.get(), inotify_.get());
  watch_input_dir();
}

Keyboards::~Keyboards() = default;

void Keyboards::watch_input_dir() {
  // IN_ATTRIB: udev may create the node first and give it its group a moment later, so a keyboard
  // that could not be opened is tried again when its permissions change.
  dir_watch_ = inotify_add_watch(inotify_.get(), input_dir_.c_str(), IN_CREATE | IN_ATTRIB | IN_MOVED_TO | IN_ONLYDIR);
  if (dir_watch_ >= 0) {
    if (parent_watch_ >= 0) inotify_rm_watch(inotify_.get(), parent_watch_);
    parent_watch_ = -1;
    scan();
    return;
  }
  // No /dev/input yet (no input device since boot): wait for the folder to appear.
  if (parent_watch_ < 0) {
    const std::string parent = std::filesystem::path(input_dir_).parent_path().string();
    parent_watch_ =
        inotify_add_watch(inotify_.get(), parent.empty() ? "/" : parent.c_str(), IN_CREATE | IN_MOVED_TO | IN_ONLYDIR);
  }
}

void Keyboards::scan() {
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(input_dir_, ec))
    if (starts_with(entry.path().filename().string(), "event")) try_open(entry.path().string());
}

void Keyboards::try_open(const std::string& path) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0 || !S_ISCHR(st.st_mode)) return;
  for (const auto& d : devices_)
    if (d->rdev == st.st_rdev) return;
  // Read-only and never EVIOCGRAB: the console and any other reader still get the keys. A device
  // this user may not read (no `input` group) is skipped; keys are an extra, not a requirement.
  base::UniqueFd fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC));
  if (!fd) return;
  auto d = std::make_unique<Device>();
  if (libevdev_new_from_fd(fd.get(), &d->dev) != 0) {
    d->dev = nullptr;
    return;
  }
  bool has_mapped_key = false;
  if (libevdev_has_event_type(d->dev, EV_KEY))
    for (unsigned code = 0; code <= KEY_MAX && !has_mapped_key; ++code)
      has_mapped_key = button_of_code_[code] >= 0 && libevdev_has_event_code(d->dev, EV_KEY, code);
  if (!has_mapped_key) return;  // a mouse, a power button, a keyboard without the board's keys
  // Input events are stamped with CLOCK_REALTIME unless asked; hal's times are monotonic.
  d->monotonic = libevdev_set_clock_id(d->dev, CLOCK_MONOTONIC) == 0;
  d->path = path;
  d->held.reserve(8);  // so a key press does not allocate
  d->rdev = st.st_rdev;
  d->fd = std::move(fd);
  epoll_watch(epoll_.get(), d->fd.get());
  devices_.push_back(std::move(d));
}

void Keyboards::drain_inotify() {
  alignas(inotify_event) std::array<char, 4096> buf;
  bool rescan = false, look_for_dir = false;
  for (;;) {
    const ssize_t n = ::read(inotify_.get(), buf.data(), buf.size());
    if (n <= 0) break;
    for (ssize_t off = 0; off < n;) {
      const auto* ev = reinterpret_cast<const inotify_event*>(buf.data() + off);
      const std::string_view name = ev->len ? std::string_view(ev->name) : std::string_view();
      if (ev->wd == dir_watch_ && starts_with(name, "event")) {
        try_open(input_dir_ + "/" + std::string(name));
      } else if (ev->wd == parent_watch_ && name == std::filesystem::path(input_dir_).filename().string()) {
        look_for_dir = true;
      }
      if (ev->mask & IN_Q_OVERFLOW) rescan = true;          // events were lost: look at the folder itself
      if (ev->mask & IN_IGNORED && ev->wd == dir_watch_) {  // the folder itself went away
        dir_watch_ = -1;
        look_for_dir = true;
      }
      off += static_cast<ssize_t>(sizeof(inotify_event) + ev->len);
    }
  }
  if (look_for_dir && dir_watch_ < 0) {
    watch_input_dir();
    // Moving the watch queued an IN_IGNORED for the old one: read it now, or the fd stays readable.
    drain_inotify();
  } else if (rescan && dir_watch_ >= 0) {
    scan();
  }
}

bool Keyboards::drain_device(Device& d, KeySink& sink) {
  unsigned flags = LIBEVDEV_READ_FLAG_NORMAL;
  for (;;) {
    input_event ev{};
    const int rc = libevdev_next_event(d.dev, flags, &ev);
    if (rc == -EAGAIN) {
      // In sync mode EAGAIN ends the replay of what a dropped buffer lost; then read on normally.
      if (flags == LIBEVDEV_READ_FLAG_SYNC) {
        flags = LIBEVDEV_READ_FLAG_NORMAL;
        continue;
      }
      return true;
    }
    if (rc == LIBEVDEV_READ_STATUS_SYNC)
      flags = LIBEVDEV_READ_FLAG_SYNC;
    else if (rc != LIBEVDEV_READ_STATUS_SUCCESS)
      return false;  // ENODEV: unplugged
    // value 2 is the keyboard's own auto-repeat; buttons repeat by their own timing.
    if (ev.type != EV_KEY || ev.code > KEY_MAX || ev.value == 2) continue;
    const int button = button_of_code_[ev.code];
    if (button < 0) continue;
    const bool pressed = ev.value != 0;
    const auto it = std::find(d.held.begin(), d.held.end(), static_cast<int>(ev.code));
    // Only the edges of this keyboard's own presses count: a key already down when the keyboard was
    // opened, or a second press event of one held, changes nothing.
    if (pressed == (it != d.held.end())) continue;
    if (pressed)
      d.held.push_back(ev.code);
    else
      d.held.erase(it);
    const Nanos t =
        d.monotonic ? std::chrono::seconds(ev.input_event_sec) + std::chrono::microseconds(ev.input_event_usec) : clock_.now();
    sink.key(static_cast<std::size_t>(button), pressed, t);
  }
}

void Keyboards::drop(std::size_t index, KeySink& sink) {
  Device& d = *devices_[index];
  epoll_ctl(epoll_.get(), EPOLL_CTL_DEL, d.fd.get(), nullptr);
  // Its keys are let go: a keyboard pulled out with a key down must not leave the button held.
  const Nanos now = clock_.now();
  for (const int code : d.held) sink.key(static_cast<std::size_t>(button_of_code_[code]), false, now);
  devices_.erase(devices_.begin() + static_cast<std::ptrdiff_t>(index));
}

void Keyboards::read(KeySink& sink) {
  if (!active_) return;
  drain_inotify();
  for (std::size_t i = 0; i < devices_.size();) {
    if (drain_device(*devices_[i], sink))
      ++i;
    else
      drop(i, sink);
  }
}

}  // namespace hal::detail
