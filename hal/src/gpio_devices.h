#pragma once
// The parts of the GPIO backends that do not need a GPIO chip: reading edge-event fds into debounced
// buttons, and LED outputs that can fail while running. GpioButtons and GpioLeds add the libgpiod
// line requests; tests drive these through pipes and fake writers.
#include <memory>
#include <string>
#include <vector>

#include "base/unique_fd.h"
#include "button_logic.h"
#include "hal/buttons.h"
#include "hal/status.h"
#include "keyboards_evdev.h"

namespace hal::detail {

// Buttons fed by libgpiod v1 line event fds, gathered with a deadline timerfd in one level-triggered
// epoll set. A line whose fd fails (ENODEV once its chip is gone, EIO at end of file) would keep
// that set readable forever and make the app's poll loop spin, so it is taken out of the set, its
// button released and the failure kept for last_error().
//
// Keyboard keys (Keyboards) can press the same buttons: a button is down while its line is active
// or any of its keys is held, and the debounce logic sees the edges of that combined level.
class EdgeButtons : public Buttons, private KeySink {
 public:
  EdgeButtons(std::vector<std::string> names, std::vector<ButtonTiming> timing, const Clock& clock);
  // Watches `fd` (owned by the caller, made non-blocking here) for `button`'s edges; `pressed` is its
  // level now, `line` names it in errors ("line GPIO17").
  void watch(std::size_t button, int fd, bool pressed, std::string line);
  // Adds keyboards as a second source of presses; their epoll set joins this one.
  void add_keyboards(std::unique_ptr<Keyboards> keyboards);
  // Keyboards open now (0 without any).
  std::size_t keyboards_open() const { return keyboards_ ? keyboards_->open_count() : 0; }

  int fd() const override { return epoll_.get(); }
  std::size_t count() const override { return names_.size(); }
  std::string_view name(std::size_t button) const override { return names_[button]; }
  std::size_t read(std::span<ButtonEvent> out) override;
  std::size_t dropped() const override { return logic_.dropped(); }
  const std::string& last_error() const override { return error_; }

 private:
  struct Line {
    std::size_t button;
    int fd;  // -1 once it failed
    std::string name;
  };
  void fail(Line& line, int err);
  void key(std::size_t button, bool pressed, Nanos time) override;
  // A line's level changed: an edge for the logic unless a key holds the button down anyway.
  void line_level(std::size_t button, bool pressed, Nanos time);

  std::vector<std::string> names_;
  ButtonLogic logic_;
  const Clock& clock_;
  base::UniqueFd epoll_;
  base::UniqueFd timer_;
  std::vector<Line> lines_;
  std::string error_;
  std::vector<bool> line_down_;           // by button: its GPIO line is active
  std::vector<unsigned> keys_down_;       // by button: keys holding it, over all keyboards
  std::unique_ptr<Keyboards> keyboards_;  // closed before the epoll set (declared after it)
};

// LED outputs whose writes can fail while running (the chip unbound or unplugged). A failing LED is
// not written again (every pattern edge would fail the same way), the failure is kept for
// last_error() and the other LEDs run on.
class OutputLeds : public LedSink {
 public:
  // `labels[i]` names LED i in errors: "LED 'status' (line GPIO23)".
  explicit OutputLeds(std::vector<std::string> labels);
  void set(std::size_t led, bool on) final;
  const std::string& last_error() const final { return error_; }

 protected:
  void disable(std::size_t led) { live_[led] = false; }  // missing at start, reported by the opener
  // Drives one LED; returns 0, or the errno of the failed write.
  virtual int write(std::size_t led, bool on) = 0;

 private:
  std::vector<std::string> labels_;
  std::vector<bool> live_;
  std::string error_;
};

}  // namespace hal::detail
