#include <cerrno>

#include "base/errno_text.h"
#include "fd.h"
#include "gpio_devices.h"
#include "gpio_line.h"
#include "hal/devices.h"

namespace hal {

namespace detail {

OutputLeds::OutputLeds(std::vector<std::string> labels) : labels_(std::move(labels)), live_(labels_.size(), true) {}

void OutputLeds::set(std::size_t led, bool on) {
  if (led >= live_.size() || !live_[led]) return;  // a missing LED was reported at start
  if (const int err = write(led, on); err != 0) {
    live_[led] = false;
    error_ =
        labels_[led] + ": set value: " + base::errno_text(err) + (err == ENODEV ? " (chip removed?)" : "") + "; LED disabled";
  }
}

}  // namespace detail

namespace {

class GpioLeds final : public detail::OutputLeds {
 public:
  GpioLeds(const std::vector<LedConfig>& leds, const std::string& consumer, std::vector<std::string>& problems)
      : OutputLeds(labels(leds)) {
    for (std::size_t i = 0; i < leds.size(); ++i) {
      std::string error;
      lines_.push_back(detail::request_line(leds[i].line, detail::LineUse::output, consumer, &error));
      if (!lines_.back().line) {
        problems.push_back("LED '" + leds[i].name + "': " + error);
        disable(i);
      }
    }
  }

 private:
  static std::vector<std::string> labels(const std::vector<LedConfig>& leds) {
    std::vector<std::string> l;
    for (const auto& led : leds) l.push_back("LED '" + led.name + "' (GPIO " + led.line.describe() + ")");
    return l;
  }
  int write(std::size_t led, bool on) override {
    errno = 0;
    if (gpiod_line_set_value(lines_[led].line.get(), on ? 1 : 0) == 0) return 0;
    return errno != 0 ? errno : EIO;
  }

  std::vector<detail::RequestedLine> lines_;
};

}  // namespace

std::unique_ptr<LedSink> open_gpio_leds(const std::vector<LedConfig>& leds, const std::string& consumer,
                                        std::vector<std::string>& problems) {
  return std::make_unique<GpioLeds>(leds, consumer, problems);
}

}  // namespace hal
