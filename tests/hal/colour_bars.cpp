#include "colour_bars.h"

#include <algorithm>
#include <cstdlib>

namespace hal::test {

RgbImage vivid_bars(int width, int height) {
  RgbImage image(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const auto& rgb = kVividBars[static_cast<std::size_t>(x * 8 / width)].rgb;
      std::uint8_t* p = image.at(x, y);
      p[0] = rgb[0];
      p[1] = rgb[1];
      p[2] = rgb[2];
    }
  return image;
}

std::vector<std::string> colour_bar_mismatches(const RgbImage& frame, int tolerance, double row_fraction) {
  // Each bar must be at least a patch wide with a pixel to spare each side, or the patch would
  // straddle two bars.
  if (frame.width < 8 * 7 || frame.height < 5 || frame.pixels.size() != static_cast<std::size_t>(frame.width) * frame.height * 3)
    return {"frame " + std::to_string(frame.width) + "x" + std::to_string(frame.height) + " (" +
            std::to_string(frame.pixels.size()) + " bytes): expected at least 56x5 RGB pixels to find 8 bars in"};
  std::vector<std::string> mismatches;
  const int cy = std::clamp(static_cast<int>(row_fraction * frame.height), 2, frame.height - 3);
  for (std::size_t bar = 0; bar < kVividBars.size(); ++bar) {
    const int left = static_cast<int>(bar) * frame.width / 8, right = (static_cast<int>(bar) + 1) * frame.width / 8;
    const int cx = (left + right) / 2;
    int sum[3] = {0, 0, 0};
    for (int y = cy - 2; y <= cy + 2; ++y)
      for (int x = cx - 2; x <= cx + 2; ++x)
        for (int c = 0; c < 3; ++c) sum[c] += frame.at(x, y)[c];
    int mean[3];
    bool off = false;
    for (int c = 0; c < 3; ++c) {
      mean[c] = (sum[c] + 12) / 25;
      off = off || std::abs(mean[c] - kVividBars[bar].rgb[static_cast<std::size_t>(c)]) > tolerance;
    }
    if (!off) continue;
    const auto& want = kVividBars[bar].rgb;
    mismatches.push_back("bar " + std::to_string(bar) + " (" + kVividBars[bar].name + ") at (" + std::to_string(cx) + ", " +
                         std::to_string(cy) + "): expected RGB " + std::to_string(want[0]) + " " + std::to_string(want[1]) + " " +
                         std::to_string(want[2]) + " within " + std::to_string(tolerance) + ", got " + std::to_string(mean[0]) +
                         " " + std::to_string(mean[1]) + " " + std::to_string(mean[2]));
  }
  return mismatches;
}

}  // namespace hal::test
