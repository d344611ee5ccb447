#pragma once
// Where the play loop's events come from, each an fd in one poll: signals (signalfd), changes to
// the content's files (inotify), the board's buttons as actions, and the poll over all of them.
// Each reads without blocking and hands back plain data; what the events do is the loop's affair.
#include "base/unique_fd.h"
#include "hal/board.h"
#include "hal/buttons.h"

#include <poll.h>

#include <array>
#include <initializer_list>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <vector>

namespace hal {
class MockButtons;
}

namespace app {

// SIGTERM and SIGINT stop, SIGHUP reloads the playlist and every scene, SIGUSR1 asks for a display
// self-check. Blocked in every thread (threads started later inherit the mask), read through a signalfd.
class SignalSource {
 public:
  struct Received {
    bool stop = false, check = false;
    int reloads = 0;
  };
  // False when the signalfd cannot be made.
  bool open();
  int fd() const { return fd_.get(); }
  Received drain();

 private:
  base::UniqueFd fd_;
};

// Folders of the playlist and of every item's scene and display: a writer saves a dot-file and
// renames it into place (MOVED_TO), or writes in place (CLOSE_WRITE); a removed file (DELETE)
// fails its next load.
class ContentWatch {
 public:
  struct Change {
    std::string path;
    bool deleted = false;
  };
  // False and why when inotify cannot be had: the content is then not watched.
  bool open(std::string& error);
  int fd() const { return fd_.get(); }
  // Watches the folders not watched yet; a folder that cannot be watched is added to `problems`.
  void watch(const std::set<std::string>& folders, std::vector<std::string>& problems);
  // The files changed since the last call (dot-files, writers' temporaries, left out), into `out`.
  void drain(std::vector<Change>& out);

 private:
  base::UniqueFd fd_;
  std::map<int, std::string> folders_;  // watch descriptor -> folder
};

// The board's buttons as the actions the board file gives them. A button with a long-press action
// acts on release of a short press, so a long press does not first do the short action; one without
// acts at once on press (and on each repeat).
class ButtonActions {
 public:
  // `mock`: the mock backend's buttons, which a window's keys press; null with real buttons.
  ButtonActions(std::vector<hal::ButtonConfig> buttons, hal::MockButtons* mock);
  // Every pending event of `buttons`, appended to `out` as actions in order.
  void read(hal::Buttons& buttons, std::vector<hal::Action>& out);
  // A window's key (named as board files name it) presses or releases the mock buttons bound to it.
  void key(std::string_view key, bool pressed);

 private:
  std::vector<hal::ButtonConfig> buttons_;  // actions per button index
  hal::MockButtons* mock_;
  std::array<bool, 256> long_fired_{};
};

// The poll over every source, made anew each wait (sources come and go: a camera, a display).
class PollSet {
 public:
  // Waits until one of `fds` or `more` is readable or `timeout_ms` passes; negative fds are left out.
  void wait(std::initializer_list<int> fds, const std::vector<int>& more, int timeout_ms);
  // Whether the last wait() found `fd` readable (or hung up, or in error).
  bool readable(int fd) const;
  // Waits for one fd alone.
  static void wait_one(int fd, int timeout_ms);

 private:
  std::vector<pollfd> fds_;
};

}  // namespace app
