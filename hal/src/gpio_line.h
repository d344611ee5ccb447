#pragma once
// libgpiod 1.6 lines with owned chips. A line found by name opens its own chip, so each requested
// line keeps its chip handle alive next to it.
#include <gpiod.h>

#include <memory>
#include <string>

#include "hal/board.h"

namespace hal::detail {

using ChipPtr = std::unique_ptr<gpiod_chip, decltype(&gpiod_chip_close)>;

struct LineRelease {
  void operator()(gpiod_line* l) const { gpiod_line_release(l); }
};

// Released before the chip closes (member order).
struct RequestedLine {
  ChipPtr chip{nullptr, &gpiod_chip_close};
  std::unique_ptr<gpiod_line, LineRelease> line;
};

enum class LineUse { both_edges, output };

// Requests a line; on failure returns an empty line and sets *error to a message naming it.
RequestedLine request_line(const GpioLine& cfg, LineUse use, const std::string& consumer, std::string* error);

}  // namespace hal::detail
