#include "gpio_line.h"
#include "hal/devices.h"

namespace hal {

namespace {

class GpioLeds final : public LedSink {
public:
  GpioLeds(const std::vector<LedConfig>& leds, const std::string& consumer, std::vector<std::string>& problems) {
    for (const auto& led : leds) {
      std::string error;
      lines_.push_back(detail::request_line(led.line, detail::LineUse::Output, consumer, &error));
      if (!lines_.back().line) problems.push_back("LED '" + led.name + "': " + error);
    }
  }
  void set(std::size_t led, bool on) override {
    // A missing LED was reported at start; the patterns run on without it.
    if (led < lines_.size() && lines_[led].line) gpiod_line_set_value(lines_[led].line.get(), on ? 1 : 0);
  }

private:
  std::vector<detail::RequestedLine> lines_;
};

}  // namespace

std::unique_ptr<LedSink> open_gpio_leds(const std::vector<LedConfig>& leds, const std::string& consumer,
                                        std::vector<std::string>& problems) {
  return std::make_unique<GpioLeds>(leds, consumer, problems);
}

}  // namespace hal
