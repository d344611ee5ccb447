#pragma once
// The test pattern vivid (the kernel's virtual V4L2 camera) shows by default, and a check that a
// captured frame is that pattern: a capture that returns the right size but garbled, swapped or
// blank pixels must fail, not just a capture of the wrong size.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "hal/image.h"

namespace hal::test {

// v4l2-tpg's "75% Colorbar" (drivers/media/common/v4l2-tpg, pattern 0, vivid's default): eight
// vertical bars of equal width, bar i covering x in [i*w/8, (i+1)*w/8), in these sRGB colours.
// Its white is the 75% grey (191), its black full black.
struct Bar {
  const char* name;
  std::array<std::uint8_t, 3> rgb;
};
inline constexpr std::array<Bar, 8> kVividBars = {{{"white", {191, 191, 191}},
                                                   {"yellow", {191, 191, 0}},
                                                   {"cyan", {0, 191, 191}},
                                                   {"green", {0, 191, 0}},
                                                   {"magenta", {191, 0, 191}},
                                                   {"red", {191, 0, 0}},
                                                   {"blue", {0, 0, 191}},
                                                   {"black", {0, 0, 0}}}};

// Draws the pattern: what a perfect capture of vivid looks like.
RgbImage vivid_bars(int width, int height);

// Compares the mean of a 5x5 patch at each bar's centre, on a row `row_fraction` down the frame,
// with the bar's colour. vivid writes its text overlay into the top rows and nothing below them,
// so a row well below the top (the default 0.8) sees only the bars. Returns one line per bar whose
// channels differ by more than `tolerance`, naming the bar, where it was sampled, what was expected
// and what was found; empty when every bar matches.
std::vector<std::string> colour_bar_mismatches(const RgbImage& frame, int tolerance, double row_fraction = 0.8);

}  // namespace hal::test
