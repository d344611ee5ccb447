#include "gpio_line.h"

#include <cerrno>

#include "base/errno_text.h"
#include "fd.h"

namespace hal::detail {

RequestedLine request_line(const GpioLine& cfg, LineUse use, const std::string& consumer, std::string* error) {
  RequestedLine r;
  gpiod_line* line = nullptr;
  if (!cfg.line_name.empty() && cfg.chip.empty()) {
    // gpiod_line_find scans every chip and returns the line with its chip opened for us.
    errno = 0;
    line = gpiod_line_find(cfg.line_name.c_str());
    if (!line) {
      *error = "GPIO " + cfg.describe() + ": no chip has a line of that name" +
               (errno ? " (" + base::errno_text(errno) + ")" : std::string());
      return r;
    }
    r.chip.reset(gpiod_line_get_chip(line));
  } else {
    r.chip.reset(gpiod_chip_open_lookup(cfg.chip.c_str()));
    if (!r.chip) {
      *error = "GPIO chip '" + cfg.chip + "' for " + cfg.describe() + ": cannot open: " + base::errno_text(errno);
      return r;
    }
    line = cfg.line_name.empty() ? gpiod_chip_get_line(r.chip.get(), static_cast<unsigned>(cfg.offset))
                                 : gpiod_chip_find_line(r.chip.get(), cfg.line_name.c_str());
    if (!line) {
      const unsigned n = gpiod_chip_num_lines(r.chip.get());
      *error = "GPIO " + cfg.describe() + ": no such line on " + cfg.chip + " (it has " + std::to_string(n) +
               " lines, offsets 0.." + std::to_string(n ? n - 1 : 0) + ")";
      return r;
    }
  }
  int flags = cfg.active_low ? GPIOD_LINE_REQUEST_FLAG_ACTIVE_LOW : 0;
  switch (cfg.bias) {
    case Bias::as_is:
      break;
    case Bias::disable:
      flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_DISABLE;
      break;
    case Bias::pull_up:
      flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_UP;
      break;
    case Bias::pull_down:
      flags |= GPIOD_LINE_REQUEST_FLAG_BIAS_PULL_DOWN;
      break;
  }
  gpiod_line_request_config req{
      consumer.c_str(), use == LineUse::output ? GPIOD_LINE_REQUEST_DIRECTION_OUTPUT : GPIOD_LINE_REQUEST_EVENT_BOTH_EDGES,
      flags};
  if (gpiod_line_request(line, &req, 0) != 0) {
    const char* user = gpiod_line_consumer(line);
    *error = "GPIO " + cfg.describe() + ": cannot request " +
             (use == LineUse::output ? std::string("as output") : std::string("for edge events")) + ": " +
             base::errno_text(errno) + (user ? std::string(" (used by '") + user + "')" : std::string());
    return r;
  }
  r.line.reset(line);
  return r;
}

}  // namespace hal::detail
