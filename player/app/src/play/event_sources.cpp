#include "play/event_sources.h"

#include "hal/mock.h"

#include <signal.h>
#include <sys/inotify.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace app {

namespace fs = std::filesystem;

bool SignalSource::open() {
  sigset_t signals;
  sigemptyset(&signals);
  for (int signal : {SIGTERM, SIGINT, SIGHUP, SIGUSR1}) sigaddset(&signals, signal);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  fd_.reset(signalfd(-1, &signals, SFD_NONBLOCK | SFD_CLOEXEC));
  return static_cast<bool>(fd_);
}

SignalSource::Received SignalSource::drain() {
  Received received;
  signalfd_siginfo info{};
  while (read(fd_.get(), &info, sizeof info) == static_cast<ssize_t>(sizeof info)) {
    switch (info.ssi_signo) {
      case SIGTERM:
      case SIGINT:
        received.stop = true;
        break;
      case SIGHUP:
        ++received.reloads;
        break;
      case SIGUSR1:
        received.check = true;
        break;
      default:
        break;
    }
  }
  return received;
}

bool ContentWatch::open(std::string& error) {
  fd_.reset(inotify_init1(IN_NONBLOCK | IN_CLOEXEC));
  if (fd_) return true;
  error = "inotify: cannot watch the content for changes (" + std::string(std::strerror(errno)) + ")";
  return false;
}

void ContentWatch::watch(const std::set<std::string>& folders, std::vector<std::string>& problems) {
  if (!fd_) return;
  for (const std::string& folder : folders) {
    bool known = false;
    for (const auto& [wd, dir] : folders_) known = known || dir == folder;
    if (known) continue;
    const int wd = inotify_add_watch(fd_.get(), folder.c_str(), IN_CLOSE_WRITE | IN_MOVED_TO | IN_DELETE);
    if (wd >= 0)
      folders_[wd] = folder;
    else
      problems.push_back(folder + ": cannot watch for changes (" + std::string(std::strerror(errno)) + ")");
  }
}

void ContentWatch::drain(std::vector<Change>& out) {
  alignas(inotify_event) char buffer[4096];
  for (;;) {
    const ssize_t n = read(fd_.get(), buffer, sizeof buffer);
    if (n <= 0) return;
    for (ssize_t at = 0; at < n;) {
      const auto* event = reinterpret_cast<const inotify_event*>(buffer + at);
      at += static_cast<ssize_t>(sizeof(inotify_event) + event->len);
      if (event->len == 0 || event->name[0] == '.') continue;  // dot-files are writers' temporaries
      const auto folder = folders_.find(event->wd);
      if (folder == folders_.end()) continue;
      out.push_back({(fs::path(folder->second) / event->name).string(), (event->mask & IN_DELETE) != 0});
    }
  }
}

ButtonActions::ButtonActions(std::vector<hal::ButtonConfig> buttons, hal::MockButtons* mock)
    : buttons_(std::move(buttons)), mock_(mock) {}

void ButtonActions::read(hal::Buttons& buttons, std::vector<hal::Action>& out) {
  std::array<hal::ButtonEvent, 32> events;
  for (;;) {
    const size_t n = buttons.read(events);
    for (size_t i = 0; i < n; ++i) {
      const hal::ButtonEvent& event = events[i];
      if (event.button >= buttons_.size()) continue;
      const hal::ButtonConfig& button = buttons_[event.button];
      const bool has_long = button.long_action != hal::Action::none;
      switch (event.action) {
        case hal::ButtonAction::press:
          if (!has_long) out.push_back(button.action);
          long_fired_[event.button] = false;
          break;
        case hal::ButtonAction::repeat:
          if (!has_long) out.push_back(button.action);
          break;
        case hal::ButtonAction::long_press:
          if (has_long) {
            out.push_back(button.long_action);
            long_fired_[event.button] = true;
          }
          break;
        case hal::ButtonAction::release:
          if (has_long && !long_fired_[event.button]) out.push_back(button.action);
          break;
      }
    }
    if (n < events.size()) break;
  }
}

void ButtonActions::key(std::string_view key, bool pressed) {
  if (mock_ == nullptr) return;
  for (size_t b = 0; b < buttons_.size(); ++b)
    if (!buttons_[b].key.empty() && buttons_[b].key == key) mock_->inject(b, pressed);
}

void PollSet::wait(std::initializer_list<int> fds, const std::vector<int>& more, int timeout_ms) {
  fds_.clear();
  for (int fd : fds)
    if (fd >= 0) fds_.push_back({fd, POLLIN, 0});
  for (int fd : more)
    if (fd >= 0) fds_.push_back({fd, POLLIN, 0});
  poll(fds_.data(), fds_.size(), timeout_ms);
}

bool PollSet::readable(int fd) const {
  for (const pollfd& p : fds_)
    if (p.fd == fd) return p.revents != 0;
  return false;
}

void PollSet::wait_one(int fd, int timeout_ms) {
  pollfd wake{fd, POLLIN, 0};
  poll(&wake, 1, timeout_ms);
}

}  // namespace app
