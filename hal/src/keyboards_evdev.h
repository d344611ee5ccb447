#pragma once
// Keys of USB (or any evdev) keyboards as buttons on the linux backend: a key whose name is a
// button's `key` presses that button, as the window platform's keys do on a desktop. Keyboards are
// found in /dev/input at start and while running (inotify), read without grabbing them, and one that
// goes away releases the keys it held.
#include <memory>
#include <string>
#include <vector>

#include "base/unique_fd.h"
#include "hal/clock.h"

struct libevdev;

namespace hal::detail {

// The board file's name of an evdev key code: SDL's key name in lower case, as the window platform
// uses them ("space", "n", "right", "f11", "return", "escape", "left ctrl", "keypad 1"); "" for a
// code that is no key (buttons of mice and joysticks, unknown codes).
std::string board_key_name(unsigned code);

// Gets a mapped key's press or release, with the kernel's CLOCK_MONOTONIC time of the key event.
class KeySink {
 public:
  virtual void key(std::size_t button, bool pressed, Nanos time) = 0;

 protected:
  ~KeySink() = default;
};

class Keyboards {
 public:
  // keys[i] is button i's key name ("" for none). `input_dir` is where event devices appear
  // (/dev/input; the folder itself may appear later, as on a board that boots without a keyboard).
  // Never throws for a missing or unreadable device; std::system_error only if inotify or epoll
  // cannot be created.
  Keyboards(const std::vector<std::string>& keys, std::string input_dir, const Clock& clock);
  ~Keyboards();
  Keyboards(const Keyboards&) = delete;
  Keyboards& operator=(const Keyboards&) = delete;

  // Readable when a keyboard has events or /dev/input changed (an epoll set; level-triggered).
  int fd() const { return epoll_.get(); }
  // Opens keyboards that appeared, reads every pending key event, drops keyboards that went away
  // (releasing their held keys), and passes the mapped keys' edges to `sink`. Allocates only when a
  // keyboard is plugged in.
  void read(KeySink& sink);
  // Keyboards open now (devices with at least one of the mapped keys).
  std::size_t open_count() const { return devices_.size(); }
  // Whether any button has a key; without one nothing is watched.
  bool active() const { return active_; }

 private:
  struct Device;
  void watch_input_dir();
  void scan();
  void try_open(const std::string& path);
  void drain_inotify();
  bool drain_device(Device& d, KeySink& sink);  // false once the device is gone
  void drop(std::size_t index, KeySink& sink);

  std::vector<int> button_of_code_;  // by key code: the button index, -1 for none
  std::string input_dir_;
  const Clock& clock_;
  bool active_ = false;
  base::UniqueFd epoll_;
  base::UniqueFd inotify_;
  int dir_watch_ = -1;     // on input_dir_
  int parent_watch_ = -1;  // on its parent, until input_dir_ exists
  std::vector<std::unique_ptr<Device>> devices_;
};

}  // namespace hal::detail
