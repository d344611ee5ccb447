#include <fcntl.h>
#include <sys/epoll.h>

#include <array>
#include <cerrno>
#include <system_error>

#include "base/errno_text.h"
#include "fd.h"
#include "gpio_devices.h"
#include "gpio_line.h"
#include "hal/devices.h"

namespace hal {

namespace detail {

EdgeButtons::EdgeButtons(std::vector<std::string> names, std::vector<ButtonTiming> timing, const Clock& clock)
    : names_(std::move(names)),
      logic_(std::move(timing)),
      clock_(clock),
      epoll_(make_epoll()),
      timer_(make_timer()),
      line_down_(names_.size(), false),
      keys_down_(names_.size(), 0) {
  epoll_watch(epoll_.get(), timer_.get());
}

void EdgeButtons::add_keyboards(std::unique_ptr<Keyboards> keyboards) {
  if (!keyboards->active()) return;  // no button has a key: nothing to watch
  epoll_watch(epoll_.get(), keyboards->fd());
  keyboards_ = std::move(keyboards);
}

void EdgeButtons::line_level(std::size_t button, bool pressed, Nanos time) {
  line_down_[button] = pressed;
  if (keys_down_[button] == 0) logic_.edge(button, pressed, time);
}

void EdgeButtons::key(std::size_t button, bool pressed, Nanos time) {
  const bool was_down = line_down_[button] || keys_down_[button] > 0;
  if (pressed)
    ++keys_down_[button];
  else if (keys_down_[button] > 0)
    --keys_down_[button];
  const bool down = line_down_[button] || keys_down_[button] > 0;
  if (down != was_down) logic_.edge(button, down, time);
}

void EdgeButtons::watch(std::size_t button, int fd, bool pressed, std::string line) {
  // The v1 event fd blocks on read; non-blocking lets read() drain it without a poll per line.
  fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
  epoll_watch(epoll_.get(), fd);
  logic_.set_initial(button, pressed);
  line_down_[button] = pressed;
  lines_.push_back({button, fd, std::move(line)});
}

std::size_t EdgeButtons::read(std::span<ButtonEvent> out) {
  // fd() is a level-triggered epoll set: once every member is drained it stops being readable.
  drain(timer_.get());
  for (Line& l : lines_) {
    if (l.fd < 0) continue;
    std::array<gpiod_line_event, 16> events;
    int n = 0;
    while ((n = gpiod_line_event_read_fd_multiple(l.fd, events.data(), static_cast<unsigned>(events.size()))) > 0) {
      for (int k = 0; k < n; ++k) {
        // Since Linux 5.7 v1 line events are stamped with CLOCK_MONOTONIC, hal's clock. Active-low is
        // applied by the kernel, so a rising edge is always "pressed".
        const Nanos t = std::chrono::seconds(events[k].ts.tv_sec) + Nanos(events[k].ts.tv_nsec);
        line_level(l.button, events[k].event_type == GPIOD_LINE_EVENT_RISING_EDGE, t);
      }
    }
    // n < 0 always ends the loop: EAGAIN means drained; anything else will not go away.
    if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) fail(l, errno);
  }
  if (keyboards_) keyboards_->read(*this);
  logic_.advance(clock_.now());
  arm_timer(timer_.get(), logic_.next_deadline());
  return logic_.drain(out);
}

void EdgeButtons::fail(Line& l, int err) {
  epoll_ctl(epoll_.get(), EPOLL_CTL_DEL, l.fd, nullptr);
  error_ = "button '" + names_[l.button] + "': GPIO " + l.name + ": reading edge events: " + base::errno_text(err) +
           (err == ENODEV ? " (chip removed?)" : "") + "; button disabled";
  // Its level is unknown from now on: treat it as let go, so the app is not left with a held button.
  line_level(l.button, false, clock_.now());
  l.fd = -1;
}

}  // namespace detail

namespace {

class GpioButtons final : public detail::EdgeButtons {
 public:
  GpioButtons(const std::vector<ButtonConfig>& buttons, const std::string& consumer, const Clock& clock,
              std::vector<std::string>& problems)
      : EdgeButtons(names(buttons), timings(buttons), clock) {
    for (std::size_t i = 0; i < buttons.size(); ++i) {
      std::string error;
      detail::RequestedLine l = detail::request_line(buttons[i].line, detail::LineUse::both_edges, consumer, &error);
      if (!l.line) {
        problems.push_back("button '" + buttons[i].name + "': " + error);
        continue;
      }
      const bool pressed = gpiod_line_get_value(l.line.get()) == 1;
      watch(i, gpiod_line_event_get_fd(l.line.get()), pressed, buttons[i].line.describe());
      lines_.push_back(std::move(l));
    }
  }

 private:
  static std::vector<std::string> names(const std::vector<ButtonConfig>& b) {
    std::vector<std::string> n;
    for (const auto& c : b) n.push_back(c.name);
    return n;
  }
  static std::vector<ButtonTiming> timings(const std::vector<ButtonConfig>& b) {
    std::vector<ButtonTiming> t;
    for (const auto& c : b) t.push_back(c.timing);
    return t;
  }

  // Released (closing the event fds) before the base's epoll set closes.
  std::vector<detail::RequestedLine> lines_;
};

}  // namespace

std::unique_ptr<Buttons> open_gpio_buttons(const std::vector<ButtonConfig>& buttons, const std::string& consumer,
                                           const Clock& clock, std::vector<std::string>& problems) {
  return std::make_unique<GpioButtons>(buttons, consumer, clock, problems);
}

std::unique_ptr<Buttons> open_linux_buttons(const std::vector<ButtonConfig>& buttons, const std::string& consumer,
                                            const Clock& clock, std::vector<std::string>& problems,
                                            const std::string& input_dir) {
  auto b = std::make_unique<GpioButtons>(buttons, consumer, clock, problems);
  std::vector<std::string> keys;
  for (const ButtonConfig& c : buttons) keys.push_back(c.key);
  try {
    b->add_keyboards(std::make_unique<detail::Keyboards>(keys, input_dir, clock));
  } catch (const std::system_error& e) {
    problems.push_back("keyboards: cannot watch " + input_dir + ": " + e.what());
  }
  return b;
}

}  // namespace hal
