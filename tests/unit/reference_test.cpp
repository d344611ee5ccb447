// The CPU reference on synthetic depth images whose AO is known in closed form.
#include "ssao/params.h"
#include "ssao/reference.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace {

constexpr int kSize = 64;

// What the sphere estimator gives on an unbounded plane facing the camera: the share of kernel
// samples farther than the bias behind the plane. The turn about the view axis leaves z alone.
float plane_prediction(const shared_layout::SsaoParams& params) {
  int behind = 0;
  for (int i = 0; i < params.counts.x; ++i) behind += params.kernel[i].z < -params.radius_4_bias.y ? 1 : 0;
  return static_cast<float>(behind) / static_cast<float>(params.counts.x);
}

class ReferenceOnPlane : public ::testing::TestWithParam<ssao::Pattern> {};

TEST_P(ReferenceOnPlane, FacingPlaneGetsThePredictedValueAndBackgroundGetsZero) {
  const glm::mat4 projection = glm::perspective(glm::radians(45.0f), 1.0f, 0.5f, 20.0f);
  ssao::AoSettings settings;
  settings.pattern = GetParam();
  settings.samples = 16;
  const float depth = 5.0f, radius = 0.3f;
  const auto params = ssao::make_ssao_params(settings, radius, projection, kSize, kSize);
  // A plane at depth 5 covering the image but for a background strip on the left.
  std::vector<float> image(kSize * kSize, depth);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < 4; ++x) image[static_cast<size_t>(y * kSize + x)] = 0.0f;
  const auto ao = ssao::reference_ssao(image, params, 1.0f / 20.0f);
  const float expected = plane_prediction(params);
  ASSERT_GT(expected, 0.0f);
  // The largest radius spans 0.3 / (5 * tan(22.5 deg)) * 32 = 4.6 pixels: stay 6 pixels off every edge.
  for (int y = 6; y < kSize - 6; ++y)
    for (int x = 10; x < kSize - 6; ++x) EXPECT_NEAR(ao[static_cast<size_t>(y * kSize + x)].x, expected, 1e-3) << x << "," << y;
  for (int y = 0; y < kSize; ++y) EXPECT_EQ(ao[static_cast<size_t>(y * kSize)].x, 0.0f);
  EXPECT_NEAR(ao[static_cast<size_t>(32 * kSize + 32)].y, depth / 20.0f, 1e-3);
}

INSTANTIATE_TEST_SUITE_P(AllPatterns, ReferenceOnPlane,
                         ::testing::Values(ssao::Pattern::random, ssao::Pattern::jittered, ssao::Pattern::latin,
                                           ssao::Pattern::poisson),
                         [](const auto& param_info) { return std::string(ssao::name(param_info.param)); });

TEST(Reference, StepEdgeOccludesTheLowerSideOnly) {
  // Left half of the image is a plane at depth 5, right half a plane at depth 4.8 (closer): the step's
  // foot (far side, next to the closer wall) gains occlusion; the top of the step does not.
  const glm::mat4 projection = glm::perspective(glm::radians(45.0f), 1.0f, 0.5f, 20.0f);
  ssao::AoSettings settings;
  settings.samples = 32;
  settings.radii = 1;
  const auto params = ssao::make_ssao_params(settings, 0.4f, projection, kSize, kSize);
  std::vector<float> image(kSize * kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) image[static_cast<size_t>(y * kSize + x)] = x < kSize / 2 ? 5.0f : 4.8f;
  const auto ao = ssao::reference_ssao(image, params, 1.0f / 20.0f);
  const float flat = plane_prediction(params);
  EXPECT_GT(ao[static_cast<size_t>(32 * kSize + kSize / 2 - 2)].x, flat + 0.05f);  // the foot of the step
  EXPECT_NEAR(ao[static_cast<size_t>(32 * kSize + kSize / 2 + 8)].x, flat, 1e-3);   // on top, far from the edge
}

TEST(Reference, RangeCheckIgnoresFarOccluders) {
  // A plane at depth 5 with a near object at depth 1 covering the right half: the object is 4 units
  // in front, beyond every radius, so the plane next to it keeps the flat value (no halo).
  const glm::mat4 projection = glm::perspective(glm::radians(45.0f), 1.0f, 0.5f, 20.0f);
  ssao::AoSettings settings;
  settings.samples = 16;
  const auto params = ssao::make_ssao_params(settings, 0.3f, projection, kSize, kSize);
  std::vector<float> image(kSize * kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) image[static_cast<size_t>(y * kSize + x)] = x < kSize / 2 ? 5.0f : 1.0f;
  const auto ao = ssao::reference_ssao(image, params, 1.0f / 20.0f);
  // Without the check the near object would hide nearly every sample (AO near 1); with it, the
  // pixel never exceeds what the plane alone gives.
  EXPECT_LE(ao[static_cast<size_t>(32 * kSize + kSize / 2 - 2)].x, plane_prediction(params) + 1e-3);
}

TEST(Reference, GaussianBlurPreservesAConstantAndBilateralStopsAtDepthEdges) {
  constexpr int w = 32, h = 8;
  ssao::BlurSettings blur;
  std::vector<ssao::AoTexel> constant(w * h, ssao::AoTexel(0.25f, 0.5f));
  const auto params = ssao::make_blur_params(blur, 0, w, h);
  for (const auto& texel : ssao::reference_blur(constant, params, false)) EXPECT_NEAR(texel.x, 0.25f, 1e-3);
  // AO 1 at depth 0.2 on the left, AO 0 at depth 0.6 on the right.
  std::vector<ssao::AoTexel> edge(w * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) edge[static_cast<size_t>(y * w + x)] = x < w / 2 ? ssao::AoTexel(1.0f, 0.2f) : ssao::AoTexel(0.0f, 0.6f);
  const auto gaussian = ssao::reference_blur(edge, params, false);
  const auto bilateral = ssao::reference_blur(edge, params, true);
  const size_t left = static_cast<size_t>(4 * w + w / 2 - 1), right = left + 1;
  EXPECT_LT(gaussian[left].x, 0.9f);   // the plain Gaussian bleeds across the edge
  EXPECT_GT(gaussian[right].x, 0.1f);
  EXPECT_NEAR(bilateral[left].x, 1.0f, 1e-3);  // the bilateral one does not
  EXPECT_NEAR(bilateral[right].x, 0.0f, 1e-3);
}

}  // namespace
