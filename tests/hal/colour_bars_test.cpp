// The vivid colour-bar check on synthetic frames, so a check that passes anything (or only the size)
// fails here, where no vivid device exists.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "colour_bars.h"
#include "hal/convert.h"

namespace hal::test {
namespace {

using Mismatches = std::vector<std::string>;

// What vivid sends for YUYV: BT.601 limited-range Y'CbCr, chroma shared by each pixel pair.
std::vector<std::uint8_t> to_yuyv(const RgbImage& rgb) {
  std::vector<std::uint8_t> out(static_cast<std::size_t>(rgb.width) * rgb.height * 2);
  auto q = [](double v) { return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L)); };
  for (int y = 0; y < rgb.height; ++y)
    for (int x = 0; x + 1 < rgb.width; x += 2) {
      double luma[2], cb = 0.0, cr = 0.0;
      for (int i = 0; i < 2; ++i) {
        const std::uint8_t* p = rgb.at(x + i, y);
        const double r = p[0] / 255.0, g = p[1] / 255.0, b = p[2] / 255.0;
        luma[i] = 16.0 + 65.481 * r + 128.553 * g + 24.966 * b;
        cb += 0.5 * (128.0 - 37.797 * r - 74.203 * g + 112.0 * b);
        cr += 0.5 * (128.0 + 112.0 * r - 93.786 * g - 18.214 * b);
      }
      std::uint8_t* d = &out[(static_cast<std::size_t>(y) * rgb.width + x) * 2];
      d[0] = q(luma[0]);
      d[1] = q(cb);
      d[2] = q(luma[1]);
      d[3] = q(cr);
    }
  return out;
}

// The tolerance the vivid capture test uses; see VividCapture in linux_test.cpp for why.
constexpr int kVividTolerance = 8;

TEST(ColourBars, ThePatternItselfMatchesExactly) {
  EXPECT_EQ(colour_bar_mismatches(vivid_bars(640, 480), 0), Mismatches{});
  EXPECT_EQ(colour_bar_mismatches(vivid_bars(1280, 720), 0), Mismatches{});
}

TEST(ColourBars, PatternThroughYuyvIsWithinTheCaptureTolerance) {
  const RgbImage bars = vivid_bars(640, 480);
  const std::vector<std::uint8_t> yuyv = to_yuyv(bars);
  RgbImage back(640, 480);
  yuyv_to_rgb(yuyv, 640, 480, 640 * 2, back);
  EXPECT_EQ(colour_bar_mismatches(back, kVividTolerance), Mismatches{});
  // The round trip is not lossless, so this shows the tolerance is needed, not just allowed.
  EXPECT_NE(back.pixels, bars.pixels);
}

TEST(ColourBars, UniformFrameFailsEveryBar) {
  RgbImage grey(640, 480);
  std::fill(grey.pixels.begin(), grey.pixels.end(), std::uint8_t{128});
  const Mismatches m = colour_bar_mismatches(grey, kVividTolerance);
  ASSERT_EQ(m.size(), 8u);
  EXPECT_EQ(m[0], "bar 0 (white) at (40, 384): expected RGB 191 191 191 within 8, got 128 128 128");
  EXPECT_EQ(m[7], "bar 7 (black) at (600, 384): expected RGB 0 0 0 within 8, got 128 128 128");
  EXPECT_EQ(colour_bar_mismatches(RgbImage(640, 480), kVividTolerance).size(), 7u);  // all black: only bar 7 right
}

TEST(ColourBars, SwappedChannelsFailTheBarsTheyChange) {
  RgbImage bgr = vivid_bars(640, 480);
  for (std::size_t i = 0; i < bgr.pixels.size(); i += 3) std::swap(bgr.pixels[i], bgr.pixels[i + 2]);
  const Mismatches m = colour_bar_mismatches(bgr, kVividTolerance);
  // White, green, magenta and black read the same either way round.
  ASSERT_EQ(m.size(), 4u);
  EXPECT_EQ(m[0].rfind("bar 1 (yellow)", 0), 0u) << m[0];
  EXPECT_EQ(m[1].rfind("bar 2 (cyan)", 0), 0u) << m[1];
  EXPECT_EQ(m[2].rfind("bar 5 (red)", 0), 0u) << m[2];
  EXPECT_EQ(m[3].rfind("bar 6 (blue)", 0), 0u) << m[3];
}

TEST(ColourBars, OtherPatternsAndOrdersFail) {
  // 100% bars (vivid's pattern 1): every lit channel is 255, not 191.
  RgbImage full = vivid_bars(640, 480);
  for (std::uint8_t& v : full.pixels) v = v == 191 ? 255 : v;
  EXPECT_EQ(colour_bar_mismatches(full, kVividTolerance).size(), 7u);
  // Mirrored (a horizontal flip): every bar lands on another colour.
  RgbImage mirrored = vivid_bars(640, 480);
  for (int y = 0; y < 480; ++y)
    for (int x = 0; x < 320; ++x) std::swap_ranges(mirrored.at(x, y), mirrored.at(x, y) + 3, mirrored.at(639 - x, y));
  EXPECT_EQ(colour_bar_mismatches(mirrored, kVividTolerance).size(), 8u);
  // Each row shifted one pixel more than the last (a stride one pixel too long): bars run diagonally.
  const RgbImage bars = vivid_bars(640, 480);
  RgbImage sheared(640, 480);
  for (int y = 0; y < 480; ++y)
    for (int x = 0; x < 640; ++x) std::copy_n(bars.at((x + y) % 640, 0), 3, sheared.at(x, y));
  EXPECT_FALSE(colour_bar_mismatches(sheared, kVividTolerance).empty());
}

TEST(ColourBars, FrameTooSmallOrInconsistentIsNamed) {
  EXPECT_EQ(colour_bar_mismatches(RgbImage(), kVividTolerance),
            Mismatches{"frame 0x0 (0 bytes): expected at least 56x5 RGB pixels to find 8 bars in"});
  RgbImage torn(640, 480);
  torn.pixels.resize(100);
  EXPECT_EQ(colour_bar_mismatches(torn, kVividTolerance),
            Mismatches{"frame 640x480 (100 bytes): expected at least 56x5 RGB pixels to find 8 bars in"});
}

}  // namespace
}  // namespace hal::test
