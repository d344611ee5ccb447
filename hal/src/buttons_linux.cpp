#include <fcntl.h>

#include <array>

#include "button_logic.h"
#include "fd.h"
#include "gpio_line.h"
#include "hal/devices.h"

namespace hal {

namespace {

class GpioButtons final : public Buttons {
public:
  GpioButtons(const std::vector<ButtonConfig>& buttons, const std::string& consumer, const Clock& clock,
              std::vector<std::string>& problems)
      : logic_(timings(buttons)), clock_(clock), epoll_(detail::make_epoll()), timer_(detail::make_timer()) {
    detail::epoll_watch(epoll_.get(), timer_.get());
    for (std::size_t i = 0; i < buttons.size(); ++i) {
      names_.push_back(buttons[i].name);
      std::string error;
      detail::RequestedLine l = detail::request_line(buttons[i].line, detail::LineUse::BothEdges, consumer, &error);
      if (!l.line) {
        problems.push_back("button '" + buttons[i].name + "': " + error);
        continue;
      }
      const int fd = gpiod_line_event_get_fd(l.line.get());
      // The v1 event fd blocks on read; non-blocking lets read() drain it without a poll per line.
      fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
      detail::epoll_watch(epoll_.get(), fd);
      const int value = gpiod_line_get_value(l.line.get());
      logic_.set_initial(i, value == 1);
      lines_.push_back({i, fd, std::move(l)});
    }
  }

  int fd() const override { return epoll_.get(); }
  std::size_t count() const override { return names_.size(); }
  std::string_view name(std::size_t button) const override { return names_[button]; }

  std::size_t read(std::span<ButtonEvent> out) override {
    // fd() is a level-triggered epoll set: once every member is drained it stops being readable.
    detail::drain(timer_.get());
    for (Line& l : lines_) {
      std::array<gpiod_line_event, 16> events;
      int n = 0;
      while ((n = gpiod_line_event_read_fd_multiple(l.fd, events.data(), static_cast<unsigned>(events.size()))) > 0) {
        for (int k = 0; k < n; ++k) {
          // Since Linux 5.7 v1 line events are stamped with CLOCK_MONOTONIC, hal's clock. Active-low is
          // applied by the kernel, so a rising edge is always "pressed".
          const Nanos t = std::chrono::seconds(events[k].ts.tv_sec) + Nanos(events[k].ts.tv_nsec);
          logic_.edge(l.button, events[k].event_type == GPIOD_LINE_EVENT_RISING_EDGE, t);
        }
      }
    }
    logic_.advance(clock_.now());
    detail::arm_timer(timer_.get(), logic_.next_deadline());
    return logic_.drain(out);
  }

private:
  struct Line {
    std::size_t button;
    int fd;  // owned by the line request
    detail::RequestedLine line;
  };
  static std::vector<ButtonTiming> timings(const std::vector<ButtonConfig>& b) {
    std::vector<ButtonTiming> t;
    for (const auto& c : b) t.push_back(c.timing);
    return t;
  }

  std::vector<std::string> names_;
  detail::ButtonLogic logic_;
  const Clock& clock_;
  UniqueFd epoll_;
  UniqueFd timer_;
  std::vector<Line> lines_;
};

}  // namespace

std::unique_ptr<Buttons> open_gpio_buttons(const std::vector<ButtonConfig>& buttons, const std::string& consumer,
                                           const Clock& clock, std::vector<std::string>& problems) {
  return std::make_unique<GpioButtons>(buttons, consumer, clock, problems);
}

}  // namespace hal
