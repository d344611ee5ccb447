// The error metrics on synthetic images with known answers.
#include "aoref/metrics.h"
#include "aoref/image.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace aoref {
namespace {

constexpr int kW = 40, kH = 32;

// A smooth AO pattern in [0.1, 0.9] so SSIM has structure to compare.
Image pattern() {
  Image image(kW, kH, 1);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      image.at(static_cast<size_t>(y * kW + x)) = static_cast<float>(0.5 + 0.4 * std::sin(x * 0.3) * std::cos(y * 0.2));
  return image;
}

// Depth 5 everywhere but a background band on the left (x < 4).
Image depth_with_background() {
  Image depth(kW, kH, 1, 5.0f);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < 4; ++x) depth.at(static_cast<size_t>(y * kW + x)) = 0.0f;
  return depth;
}

TEST(Metrics, IdenticalImagesHaveNoError) {
  const Image a = pattern();
  const Metrics m = compare(a, a, depth_with_background());
  EXPECT_EQ(m.mae, 0.0);
  EXPECT_EQ(m.rmse, 0.0);
  EXPECT_EQ(m.bias, 0.0);
  EXPECT_NEAR(m.ssim, 1.0, 1e-12);
  EXPECT_EQ(m.edge_mae, 0.0);
  EXPECT_EQ(m.pixels, static_cast<size_t>((kW - 4) * kH));
}

TEST(Metrics, ConstantOffsetGivesThatOffset) {
  const Image reference = pattern();
  for (float offset : {0.05f, -0.2f}) {
    Image estimate = reference;
    for (float& v : estimate.values) v += offset;
    const Metrics m = compare(estimate, reference, depth_with_background());
    // float images: the offset survives float rounding to about 1e-7 per pixel.
    EXPECT_NEAR(m.mae, std::abs(offset), 1e-6);
    EXPECT_NEAR(m.rmse, std::abs(offset), 1e-6);
    EXPECT_NEAR(m.bias, offset, 1e-6);
    EXPECT_NEAR(m.edge_mae, std::abs(offset), 1e-6);
    EXPECT_LT(m.ssim, 1.0);
  }
}

TEST(Metrics, BackgroundIsIgnored) {
  const Image reference = pattern();
  Image estimate = reference;
  for (int y = 0; y < kH; ++y) estimate.at(static_cast<size_t>(y * kW + 1)) = 1.0f;  // only background differs
  const Metrics m = compare(estimate, reference, depth_with_background());
  EXPECT_EQ(m.mae, 0.0);
  EXPECT_NEAR(m.ssim, 1.0, 1e-12);
}

TEST(Metrics, SsimFallsAsNoiseGrows) {
  const Image reference = pattern();
  double previous = 1.0;
  for (float amplitude : {0.02f, 0.1f, 0.3f}) {
    Image estimate = reference;
    uint32_t state = 12345;
    for (float& v : estimate.values) {
      state = state * 1664525u + 1013904223u;  // a fixed LCG: the test must not depend on the C++ library
      v += amplitude * (static_cast<float>(state >> 8) / 16777216.0f * 2.0f - 1.0f);
    }
    const Metrics m = compare(estimate, reference, depth_with_background());
    EXPECT_LT(m.ssim, previous) << amplitude;
    EXPECT_GT(m.mae, 0.0);
    previous = m.ssim;
  }
  EXPECT_LT(previous, 0.5);
}

TEST(Metrics, EdgeMaskMarksDepthStepsAndSilhouettesOnly) {
  // Columns 0-3 background, 4-19 a floor-like ramp (1% per column: no edge), 20-39 a step to 60% depth.
  Image depth(kW, kH, 1);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      depth.at(static_cast<size_t>(y * kW + x)) = x < 4 ? 0.0f : x < 20 ? 5.0f * (1.0f + 0.01f * static_cast<float>(x)) : 3.0f;
  MetricsSettings settings;
  settings.edge_distance = 3;
  const std::vector<uint8_t> mask = edge_mask(depth, settings);
  for (int x = 0; x < kW; ++x) {
    // Edge pixels: column 4 (next to background), 19 and 20 (the step); then 3 columns around each.
    const bool expected = x >= 4 && (x <= 4 + 3 || (x >= 19 - 3 && x <= 20 + 3));
    for (int y = 0; y < kH; ++y) ASSERT_EQ(mask[static_cast<size_t>(y * kW + x)], expected ? 1 : 0) << x << "," << y;
  }
  // Error only at the step shows up in edge_mae, diluted in mae.
  Image reference(kW, kH, 1, 0.3f), estimate = reference;
  for (int y = 0; y < kH; ++y) estimate.at(static_cast<size_t>(y * kW + 20)) = 0.7f;
  const Metrics m = compare(estimate, reference, depth, settings);
  EXPECT_NEAR(m.edge_mae, 0.4 * kH / static_cast<double>(m.edge_pixels), 1e-6);
  EXPECT_NEAR(m.mae, 0.4 * kH / static_cast<double>(m.pixels), 1e-6);
  EXPECT_EQ(m.edge_pixels, static_cast<size_t>(4 + 8) * kH);
}

TEST(Metrics, NoObjectPixelsGivesNaNAndMismatchedSizesThrow) {
  const Image empty_depth(kW, kH, 1, 0.0f);
  const Metrics m = compare(pattern(), pattern(), empty_depth);
  EXPECT_EQ(m.pixels, 0u);
  EXPECT_TRUE(std::isnan(m.mae) && std::isnan(m.rmse) && std::isnan(m.ssim) && std::isnan(m.edge_mae));
  EXPECT_THROW(compare(pattern(), Image(kW, kH + 1, 1), depth_with_background()), std::invalid_argument);
}

}  // namespace
}  // namespace aoref

namespace aoref {
namespace {

// A constant offset is bias, not noise; a checkerboard of +-d is all noise: a 5x5 box over it
// averages to about 0 (exactly +-d/25 inside), so the noise is close to d. Background pixels
// neither count nor enter the box.
TEST(Metrics, NoiseIsTheHighFrequencyPartOfTheError) {
  const Image reference = pattern();
  const Image depth = depth_with_background();
  Image offset = reference;
  for (float& v : offset.values) v += 0.1f;
  const Metrics smooth = compare(offset, reference, depth);
  EXPECT_NEAR(smooth.bias, 0.1, 1e-6);
  EXPECT_NEAR(smooth.noise, 0.0, 1e-6);
  Image dithered = reference;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) dithered.at(static_cast<size_t>(y * kW + x)) += (x + y) % 2 == 0 ? 0.05f : -0.05f;
  const Metrics noisy = compare(dithered, reference, depth);
  EXPECT_NEAR(noisy.bias, 0.0, 2e-3);
  EXPECT_NEAR(noisy.mae, 0.05, 1e-6);
  EXPECT_GT(noisy.noise, 0.045);
  EXPECT_LE(noisy.noise, 0.05 * 26.0 / 25.0 + 1e-6);
}

// A camera that moved one pixel to the right: every pixel of the new frame finds, by its world
// position, the pixel one to the left in the old one; the strip that came into view has no match.
TEST(Metrics, MatchingByReprojectionFindsTheSamePointInThePreviousFrame) {
  constexpr int w = 16, h = 8;
  // Positions on the plane z = -10 seen by an orthographic-like view-projection: x, y in [-1, 1).
  auto positions = [&](double shift) {
    Image p(w, h, 4);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = static_cast<size_t>(y * w + x);
        p.at(i, 0) = static_cast<float>((x + 0.5) / w * 2.0 - 1.0 + shift);
        p.at(i, 1) = static_cast<float>(1.0 - (y + 0.5) / h * 2.0);
        p.at(i, 2) = -10.0f;
        p.at(i, 3) = 1.0f;
      }
    return p;
  };
  const Image before = positions(0.0), now = positions(2.0 / w);  // one pixel's width further right
  glm::dmat4 view_projection(1.0);
  view_projection[3][2] = 10.0;  // z = -10 -> 0; w stays 1
  const std::vector<int64_t> match = match_previous(now, before, view_projection, glm::dvec3(0.0, 0.0, 0.0));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y * w + x);
      EXPECT_EQ(match[i], x + 1 < w ? static_cast<int64_t>(i + 1) : -1) << x << "," << y;
    }
  Image ao_before(w, h, 1), ao_now(w, h, 1);
  for (size_t i = 0; i < ao_before.values.size(); ++i) ao_before.values[i] = static_cast<float>(i % w) * 0.01f;
  for (size_t i = 0; i < ao_now.values.size(); ++i) ao_now.values[i] = static_cast<float>(i % w + 1) * 0.01f + 0.02f;
  EXPECT_NEAR(mean_change(ao_now, ao_before, match), 0.02, 1e-6);
  // A surface that was not there before (another depth) does not match.
  Image occluded = before;
  for (size_t i = 0; i < occluded.pixel_count(); ++i) occluded.at(i, 2) = -5.0f;
  for (int64_t m : match_previous(now, occluded, view_projection, glm::dvec3(0.0))) EXPECT_EQ(m, -1);
}

// The error map: white where the estimate is right, red where it is darker (more AO), blue where
// lighter, full colour at the scale and beyond, background black.
TEST(ErrorMap, ColoursTheSignedErrorAndLeavesTheBackgroundBlack) {
  Image depth(5, 1, 1, 2.0f), reference(5, 1, 1, 0.3f), estimate(5, 1, 1);
  depth.at(4) = 0.0f;
  const float values[5] = {0.3f, 0.35f, 0.1f, 0.9f, 0.5f};
  for (size_t i = 0; i < 5; ++i) estimate.at(i) = values[i];
  const std::vector<unsigned char> rgb = error_map(estimate, reference, depth, 0.1f);
  ASSERT_EQ(rgb.size(), 15u);
  const std::vector<unsigned char> expected = {255, 255, 255,  // no error
                                               255, 128, 128,  // +0.05: half red
                                               0,   0,   255,  // -0.2: beyond the scale, full blue
                                               255, 0,   0,    // +0.6: full red
                                               0,   0,   0};   // background
  for (size_t i = 0; i < rgb.size(); ++i) EXPECT_NEAR(rgb[i], expected[i], 1) << "byte " << i;
}

}  // namespace
}  // namespace aoref
