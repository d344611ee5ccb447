// The CPU reference on synthetic depth images whose AO is known in closed form.
#include "ssao/reference.h"
#include "ssao/params.h"

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace {

constexpr int kSize = 64;

// The SSAO block for a camera at the origin with a 45-degree square frustum, as the renderer makes it.
// The images here are read texel for texel at full resolution, whatever the player's default.
shared_layout::SsaoParams params_for(ssao::AoSettings settings, float radius) {
  settings.half_resolution = false;
  const glm::mat4 projection = glm::perspective(glm::radians(45.0f), 1.0f, 0.5f, 20.0f);
  auto params = ssao::pack_ssao_params(settings, radius, kSize, kSize);
  ssao::FrameView view;
  view.projection = projection;
  view.nearest_depth = view.centre_depth = 5.0f;
  view.scene_radius = 10.0f;
  ssao::update_for_frame(params, settings, view);
  return params;
}

std::vector<ssao::AoTexel> run(const std::vector<float>& depth, const shared_layout::SsaoParams& params,
                               ssao::Estimator estimator = ssao::Estimator::sphere) {
  const std::vector<glm::vec3> facing(depth.size(), glm::vec3(0, 0, 1));
  return ssao::reference_ssao(ssao::build_depth_chain(depth, kSize, kSize), facing, {}, params, 1.0f / 20.0f, estimator);
}

// What the sphere estimator gives on an unbounded plane facing the camera: the share of kernel
// samples farther than the bias behind the plane. The turn about the view axis leaves z alone.
float plane_prediction(const shared_layout::SsaoParams& params) {
  int behind = 0;
  for (int i = 0; i < params.samples; ++i) behind += params.kernel[i].z < -params.depth_bias ? 1 : 0;
  return static_cast<float>(behind) / static_cast<float>(params.samples);
}

class ReferenceOnPlane : public ::testing::TestWithParam<ssao::Pattern> {};

TEST_P(ReferenceOnPlane, FacingPlaneGetsThePredictedValueAndBackgroundGetsZero) {
  ssao::AoSettings settings;
  settings.estimator = ssao::Estimator::sphere;
  settings.radii = 5;
  settings.pattern = GetParam();
  settings.samples = 16;
  settings.depth_chain = false;
  const float depth = 5.0f, radius = 0.3f;
  const auto params = params_for(settings, radius);
  // A plane at depth 5 covering the image but for a background strip on the left.
  std::vector<float> image(kSize * kSize, depth);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < 4; ++x) image[static_cast<size_t>(y * kSize + x)] = 0.0f;
  const auto ao = run(image, params);
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
  ssao::AoSettings settings;
  settings.estimator = ssao::Estimator::sphere;
  settings.samples = 32;
  settings.radii = 1;
  const auto params = params_for(settings, 0.4f);
  std::vector<float> image(kSize * kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) image[static_cast<size_t>(y * kSize + x)] = x < kSize / 2 ? 5.0f : 4.8f;
  const auto ao = run(image, params);
  const float flat = plane_prediction(params);
  EXPECT_GT(ao[static_cast<size_t>(32 * kSize + kSize / 2 - 2)].x, flat + 0.05f);  // the foot of the step
  EXPECT_NEAR(ao[static_cast<size_t>(32 * kSize + kSize / 2 + 8)].x, flat, 1e-3);  // on top, far from the edge
}

TEST(Reference, RangeCheckIgnoresFarOccluders) {
  // A plane at depth 5 with a near object at depth 1 covering the right half: the object is 4 units
  // in front, beyond every radius, so the plane next to it keeps the flat value (no halo).
  ssao::AoSettings settings;
  settings.estimator = ssao::Estimator::sphere;
  settings.radii = 5;
  settings.samples = 16;
  const auto params = params_for(settings, 0.3f);
  std::vector<float> image(kSize * kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) image[static_cast<size_t>(y * kSize + x)] = x < kSize / 2 ? 5.0f : 1.0f;
  const auto ao = run(image, params);
  // Without the check the near object would hide nearly every sample (AO near 1); with it, the
  // pixel never exceeds what the plane alone gives.
  EXPECT_LE(ao[static_cast<size_t>(32 * kSize + kSize / 2 - 2)].x, plane_prediction(params) + 1e-3);
}

TEST(Reference, HemisphereAndHorizonGiveNoOcclusionOnAFacingPlane) {
  // Both integrate over the hemisphere above the surface, so an open plane is unoccluded (the sphere
  // estimator's 0.5 is the half of its sphere below the plane).
  std::vector<float> image(kSize * kSize, 5.0f);
  ssao::AoSettings settings;
  settings.samples = 16;
  settings.estimator = ssao::Estimator::hemisphere;
  const auto hemisphere = run(image, params_for(settings, 0.3f), settings.estimator);
  for (int y = 8; y < kSize - 8; ++y)
    for (int x = 8; x < kSize - 8; ++x) EXPECT_EQ(hemisphere[static_cast<size_t>(y * kSize + x)].x, 0.0f);
  // Away from the image centre the view vector leans off the normal, where one slice's open arc
  // integrates to 1 only on average over slice angles; the estimator's ratio of occluded to open
  // arc keeps every pixel near 0 even with a single slice (8 taps). What remains (measured up to
  // 0.006) is that taps land on texel centres, a little off the slice plane, as in XeGTAO.
  settings.estimator = ssao::Estimator::horizon;
  for (int samples : {8, 16, 64}) {
    settings.samples = samples;
    const auto horizon = run(image, params_for(settings, 0.3f), settings.estimator);
    for (int y = 8; y < kSize - 8; ++y)
      for (int x = 8; x < kSize - 8; ++x)
        EXPECT_NEAR(horizon[static_cast<size_t>(y * kSize + x)].x, 0.0f, 0.01f) << samples << " taps at " << x << "," << y;
  }
}

TEST(Reference, HemisphereSamplesDoNotHideBehindTheirOwnSlantedFace) {
  // An open plane tilted 60 degrees away from the camera, radius about 1.5 pixels: every sample lands
  // within a texel or two of the shaded one, where the stored depth (held at texel centres) differs
  // from the face under the sample by as much as the radius. Moved along the tangent plane to each
  // sample's exact position, the open face stays unoccluded.
  const glm::vec3 normal = glm::normalize(glm::vec3(0.0f, std::sin(glm::radians(60.0f)), std::cos(glm::radians(60.0f))));
  const float plane = glm::dot(normal, glm::vec3(0.0f, 0.0f, -5.0f));
  ssao::AoSettings settings;
  settings.estimator = ssao::Estimator::hemisphere;
  settings.samples = 32;
  settings.skip_radii = false;
  const auto params = params_for(settings, 0.1f);
  std::vector<float> image(kSize * kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / static_cast<float>(kSize) * 2.0f - 1.0f;
      const glm::vec3 ray(ndc.x * params.unproject.x, ndc.y * params.unproject.y, -1.0f);
      image[static_cast<size_t>(y * kSize + x)] = plane / glm::dot(normal, ray);
    }
  const std::vector<glm::vec3> normals(image.size(), normal);
  ASSERT_GT(0.1f * params.pixels_per_unit / 5.0f, 1.0f);  // the radius spans more than a pixel
  const auto ao =
      ssao::reference_ssao(ssao::build_depth_chain(image, kSize, kSize), normals, {}, params, 1.0f / 20.0f, settings.estimator);
  double sum = 0.0;
  for (int y = 4; y < kSize - 4; ++y)
    for (int x = 4; x < kSize - 4; ++x) {
      const float value = ao[static_cast<size_t>(y * kSize + x)].x;
      EXPECT_LE(value, 1.0f / 32.0f + 1e-3f) << x << "," << y;  // at most one sample off by rounding
      sum += value;
    }
  EXPECT_LT(sum / ((kSize - 8) * (kSize - 8)), 0.005);
}

TEST(Reference, HorizonSeesAStepWallAtTheFoot) {
  // The foot of a step (plane at depth 5, a closer plane at 4.8 beginning two pixels to the right):
  // the wall rises into the hemisphere, so the horizon estimator reports occlusion there.
  std::vector<float> image(kSize * kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) image[static_cast<size_t>(y * kSize + x)] = x < kSize / 2 ? 5.0f : 4.8f;
  ssao::AoSettings settings;
  settings.estimator = ssao::Estimator::horizon;
  settings.samples = 16;
  const auto ao = run(image, params_for(settings, 0.4f), ssao::Estimator::horizon);
  EXPECT_GT(ao[static_cast<size_t>(32 * kSize + kSize / 2 - 2)].x, 0.05f);
  EXPECT_NEAR(ao[static_cast<size_t>(32 * kSize + 8)].x, 0.0f, 0.01f);  // open plane, away from the step (above)
}

TEST(Reference, HorizonDarkensWhereTheShadingNormalLeansOffItsFace) {
  // A roof seen from its ridge: two planes at 30 degrees to the image plane meet along the image's
  // middle column, nearest the camera. The two columns beside the ridge carry the smooth normal of a
  // mesh (the two faces' average, facing the camera), as interpolated normals do on a coarse mesh.
  // A third of their hemisphere's cosine-weighted share lies below their own face, where a ray
  // leaves through the face at once: (1 - cos 30) / 2 of it. Every tap, 1.6 pixels out or farther,
  // lands past the ridge on the other face, which falls away: only the face's own plane finds it.
  constexpr float kTilt = glm::radians(30.0f), kRidgeDepth = 5.0f;
  ssao::AoSettings settings;
  settings.estimator = ssao::Estimator::horizon;
  settings.samples = 80;  // 8 slices of 5 taps: the slices' average is the integral over directions
  const auto params = params_for(settings, 0.3f);
  const glm::vec3 left(-std::sin(kTilt), 0.0f, std::cos(kTilt)), right(std::sin(kTilt), 0.0f, std::cos(kTilt));
  const glm::vec3 ridge(0.0f, 0.0f, -kRidgeDepth);
  std::vector<float> depth(kSize * kSize);
  std::vector<glm::vec3> shading(depth.size()), faces(depth.size());
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / static_cast<float>(kSize) * 2.0f - 1.0f;
      const glm::vec3 ray((ndc.x + params.unproject.z) * params.unproject.x, (ndc.y + params.unproject.w) * params.unproject.y,
                          -1.0f);
      // The solid lies behind both planes: a ray enters it where it crosses the later one.
      const float t_left = glm::dot(left, ridge) / glm::dot(left, ray), t_right = glm::dot(right, ridge) / glm::dot(right, ray);
      const size_t i = static_cast<size_t>(y * kSize + x);
      depth[i] = std::max(t_left, t_right);
      faces[i] = x < kSize / 2 ? left : right;
      shading[i] = x == kSize / 2 - 1 || x == kSize / 2 ? glm::vec3(0.0f, 0.0f, 1.0f) : faces[i];
    }
  const auto chain = ssao::build_depth_chain(depth, kSize, kSize);
  const auto with_faces = ssao::reference_ssao(chain, shading, faces, params, 1.0f / 20.0f, settings.estimator);
  const auto without = ssao::reference_ssao(chain, shading, {}, params, 1.0f / 20.0f, settings.estimator);
  const float expected = (1.0f - std::cos(kTilt)) / 2.0f;
  for (int y = 16; y < kSize - 16; ++y) {
    for (int x : {kSize / 2 - 1, kSize / 2}) {
      const size_t i = static_cast<size_t>(y * kSize + x);
      EXPECT_NEAR(with_faces[i].x, expected, 0.006f) << "beside the ridge at " << x << "," << y;
      EXPECT_LT(without[i].x, 0.01f) << "the taps alone, at " << x << "," << y;
    }
    for (int x : {kSize / 2 - 8, kSize / 2 + 8}) {
      const size_t i = static_cast<size_t>(y * kSize + x);
      EXPECT_LT(with_faces[i].x, 0.01f) << "on a face with its own normal, at " << x << "," << y;
    }
  }
}

TEST(Reference, DepthChainKeepsObjectDepthsAndHalvesTheSize) {
  std::vector<float> image(5 * 3, 0.0f);
  image[0] = 2.0f;
  image[1] = 4.0f;  // a 2x2 block with two object texels and two background ones
  const ssao::DepthChain chain = ssao::build_depth_chain(image, 5, 3);
  ASSERT_GE(chain.levels.size(), 3u);
  EXPECT_EQ(chain.sizes[1], glm::ivec2(2, 1));
  EXPECT_EQ(chain.sizes[2], glm::ivec2(1, 1));
  EXPECT_FLOAT_EQ(chain.at({0, 0}, 1), 3.0f);  // the mean of the object texels only
  EXPECT_FLOAT_EQ(chain.at({1, 0}, 1), 0.0f);  // all background stays background
  EXPECT_FLOAT_EQ(chain.at({0, 0}, 2), 3.0f);
}

TEST(Reference, UpsamplingInterpolatesAlongASurfaceAndNotAcrossAnEdge) {
  // Low resolution 3x1: texel 0 AO 1 and texel 1 AO 0.5 on one surface (depths 0.20 and 0.21, 5%
  // apart), texel 2 AO 0 at depth 0.6. Texel i shaded full-resolution pixel 2i.
  shared_layout::UpsampleParams params{};
  params.full_width = 6;
  params.full_height = 2;
  params.ao_width = 3;
  params.ao_height = 1;
  params.inverse_far = 1.0f;
  const std::vector<ssao::AoTexel> low = {{1.0f, 0.2f}, {0.5f, 0.21f}, {0.0f, 0.6f}};
  const std::vector<float> depth = {0.2f, 0.205f, 0.21f, 0.21f, 0.6f, 0.6f,   // row 0
                                    0.2f, 0.6f,   0.21f, 0.6f,  0.3f, 0.0f};  // row 1
  const auto full = ssao::reference_upsample(low, depth, params);
  EXPECT_EQ(full[0].x, 1.0f);   // on its own texel
  EXPECT_EQ(full[1].x, 0.75f);  // halfway along the surface: the mean of both texels
  EXPECT_EQ(full[2].x, 0.5f);
  EXPECT_EQ(full[3].x, 0.5f);  // beside an edge: only the texel on its own surface
  EXPECT_EQ(full[4].x, 0.0f);
  EXPECT_EQ(full[5].x, 0.0f);   // the image's last column reads the last texel
  EXPECT_EQ(full[6].x, 1.0f);   // row 1 reads row 0 (the only row) from below
  EXPECT_EQ(full[7].x, 0.5f);   // depth 0.6 between texels 0 and 1: neither is its surface; 1 is closer
  EXPECT_EQ(full[9].x, 0.0f);   // depth 0.6 between texels 1 and 2: texel 2's surface alone
  EXPECT_EQ(full[10].x, 0.0f);  // depth 0.3 on texel 2 (0.6): not its surface, but the only candidate
  EXPECT_EQ(full[11].x, 0.0f);  // background
  EXPECT_EQ(full[11].y, 0.0f);
}

TEST(Reference, UpsamplingWeighsTexelsOffThePixelsTangentPlaneDown) {
  // A 90-degree pinhole (unproject 1, 1, 0, 0) over 4x4 pixels and 2x2 texels. Row 0 of texels: a
  // face at depth 1.00 facing the camera (texel 0, AO 1) meets another at depth 1.04 (texel 1,
  // AO 0), within the 5% depth tolerance, so depth alone cannot tell them apart. Row 1: both texels
  // on the first face.
  shared_layout::UpsampleParams params{};
  params.full_width = params.full_height = 4;
  params.ao_width = params.ao_height = 2;
  params.inverse_far = 1.0f;
  params.plane_tolerance = 0.002f;
  params.unproject = glm::vec4(1.0f, 1.0f, 0.0f, 0.0f);
  const std::vector<ssao::AoTexel> low = {{1.0f, 1.0f}, {0.0f, 1.04f}, {1.0f, 1.0f}, {0.0f, 1.0f}};
  const std::vector<float> depth = {1.0f, 1.0f, 1.04f, 1.04f, 1.0f, 1.0f, 1.04f, 1.04f,
                                    1.0f, 1.0f, 1.0f,  1.0f,  1.0f, 1.0f, 1.0f,  1.0f};
  const glm::vec3 facing_camera(0.0f, 0.0f, 1.0f), tilted = glm::normalize(glm::vec3(-1.0f, 0.0f, 1.0f));
  std::vector<glm::vec3> normals(16, facing_camera);
  for (int y : {0, 1})
    for (int x : {2, 3}) normals[static_cast<size_t>(y * 4 + x)] = tilted;

  const auto by_depth = ssao::reference_upsample(low, depth, params);
  EXPECT_FLOAT_EQ(by_depth[1].x, 0.5f);  // the mean of both faces' texels
  const auto by_plane = ssao::reference_upsample(low, depth, params, normals);
  // Texel 1's point lies 0.04 off pixel 1's plane, 20 tolerances: weight e^-20.
  EXPECT_NEAR(by_plane[1].x, 1.0f, 1e-3f);
  EXPECT_EQ(by_plane[0].x, 1.0f);  // on its own texel, whatever the weights
  EXPECT_EQ(by_plane[9].x, 0.5f);  // row 2 lies on texel row 1: one plane, plain bilinear
  params.plane_tolerance = 0.0f;   // a tolerance of 0 turns the plane weights off
  EXPECT_FLOAT_EQ(ssao::reference_upsample(low, depth, params, normals)[1].x, 0.5f);
}

TEST(Reference, UpsamplingOnASlantedPlaneIsPlainBilinear) {
  // One plane, slanted in both directions and seen off-axis (unproject's shift), its depth at every
  // pixel's centre solved from n . (depth x ray) = -1: every texel lies on each pixel's tangent
  // plane, so the plane weights must leave the bilinear mean as it is. Both terms of a texel's
  // height over the plane (along the pixel's ray and across to the texel's pixel) are at work here.
  shared_layout::UpsampleParams params{};
  params.full_width = params.full_height = 8;
  params.ao_width = params.ao_height = 4;
  params.inverse_far = 1.0f;
  params.plane_tolerance = 0.002f;
  params.unproject = glm::vec4(0.8f, 0.6f, 0.3f, -0.2f);
  const glm::vec3 normal = glm::normalize(glm::vec3(0.5f, -0.4f, 1.0f));
  std::vector<float> depth(64);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const glm::vec2 ndc = (glm::vec2(x, y) + 0.5f) / 8.0f * 2.0f - 1.0f;
      const glm::vec3 ray((ndc.x + 0.3f) * 0.8f, (ndc.y - 0.2f) * 0.6f, -1.0f);
      depth[static_cast<size_t>(y * 8 + x)] = -1.0f / glm::dot(normal, ray);
    }
  std::vector<ssao::AoTexel> low(16);  // texel (i, j) shaded pixel (2i, 2j) and holds its depth
  for (int i = 0; i < 16; ++i)
    low[static_cast<size_t>(i)] = {0.0625f * static_cast<float>(i), depth[static_cast<size_t>((i / 4) * 16 + (i % 4) * 2)]};
  const auto by_depth = ssao::reference_upsample(low, depth, params);
  const auto by_plane = ssao::reference_upsample(low, depth, params, std::vector<glm::vec3>(64, normal));
  for (size_t i = 0; i < by_depth.size(); ++i) EXPECT_NEAR(by_plane[i].x, by_depth[i].x, 1e-3f) << "pixel " << i;
  EXPECT_NEAR(by_plane[3 * 8 + 3].x, 0.0625f * (5 + 6 + 9 + 10) / 4.0f, 1e-3f);  // between four texels
}

TEST(Frame, RadiiUnderAPixelOrBeyondTheSceneAreSkipped) {
  ssao::AoSettings settings;
  settings.estimator = ssao::Estimator::sphere;
  settings.radii = 5;
  const glm::mat4 projection = glm::perspective(glm::radians(45.0f), 1.0f, 0.5f, 200.0f);
  // Radii 8, 4, 2, 1, 0.5 in a scene of radius 1.5 seen from 100 units on a 64-pixel image (77 pixels
  // per unit at depth 1): 8 and 4 exceed the scene's diameter (3); at depth 98.5, radius 1 spans
  // 0.79 pixels and 0.5 spans 0.39, but only radii under a quarter pixel are skipped: none here.
  auto params = ssao::pack_ssao_params(settings, 8.0f, kSize, kSize);
  ssao::FrameView view;
  view.projection = projection;
  view.centre_depth = 100.0f;
  view.nearest_depth = 98.5f;
  view.scene_radius = 1.5f;
  ssao::update_for_frame(params, settings, view);
  EXPECT_EQ(params.first_radius, 1);  // radius 4 stands for everything larger than the scene
  EXPECT_EQ(params.end_radius, 5);
  EXPECT_EQ(params.skipped_radii_ao, 0.0f);
  view.nearest_depth = view.centre_depth = 400.0f;  // now 1 spans 0.19 pixels and 0.5 spans 0.1
  ssao::update_for_frame(params, settings, view);
  EXPECT_EQ(params.end_radius, 3);
  int behind = 0;
  for (int i = 0; i < params.samples; ++i) behind += params.kernel[i].z < -settings.bias ? 1 : 0;
  EXPECT_EQ(params.skipped_radii_ao, static_cast<float>(behind) / static_cast<float>(params.samples));
  settings.skip_radii = false;
  ssao::update_for_frame(params, settings, view);
  EXPECT_EQ(params.first_radius, 0);
  EXPECT_EQ(params.end_radius, 5);
  EXPECT_EQ(params.shade_background, 0);
  EXPECT_EQ(params.horizon_steps, ssao::horizon_steps(settings));
  EXPECT_EQ(params.skipped_radii_ao, 0.0f);
}

TEST(Reference, SkippedSubPixelRadiusGivesWhatComputingItGives) {
  // The sphere estimator on a slanted surface with a radius of a tenth of a pixel: the value the
  // skip substitutes equals the computed one at every pixel.
  std::vector<float> image(kSize * kSize);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) image[static_cast<size_t>(y * kSize + x)] = 5.0f + 0.02f * static_cast<float>(x);
  ssao::AoSettings settings;
  settings.estimator = ssao::Estimator::sphere;
  settings.radii = 1;
  settings.depth_chain = false;
  settings.half_resolution = false;
  const glm::mat4 projection = glm::perspective(glm::radians(45.0f), 1.0f, 0.5f, 20.0f);
  auto params = ssao::pack_ssao_params(settings, 0.01f, kSize, kSize);  // 0.01 * 77 / 5 = 0.15 pixels
  ssao::FrameView view;
  view.projection = projection;
  view.nearest_depth = view.centre_depth = 5.0f;
  view.scene_radius = 2.0f;
  settings.skip_radii = false;
  ssao::update_for_frame(params, settings, view);
  const auto computed = run(image, params);
  settings.skip_radii = true;
  ssao::update_for_frame(params, settings, view);
  ASSERT_EQ(params.end_radius, params.first_radius + 1);  // the one radius is always kept...
  settings.radii = 2;                                     // ...so skip the second of two instead
  auto two = ssao::pack_ssao_params(settings, 0.02f, kSize, kSize);
  ssao::update_for_frame(two, settings, view);
  ASSERT_EQ(two.end_radius, 1);
  two.first_radius = 0;
  two.radii[0].x = 0.0f;  // the kept radius contributes nothing, so only the substitute is left
  const auto substituted = run(image, two);
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      const size_t i = static_cast<size_t>(y * kSize + x);
      EXPECT_EQ(substituted[i].x, computed[i].x) << x << "," << y;
    }
}

TEST(Frame, LargeRadiiReadCoarserDepthLevels) {
  ssao::AoSettings settings;
  settings.radii = 5;
  settings.depth_chain = true;
  auto params = ssao::pack_ssao_params(settings, 2.0f, 1024, 768);
  ssao::FrameView view;
  view.projection = glm::perspective(glm::radians(45.0f), 4.0f / 3.0f, 0.5f, 50.0f);
  view.centre_depth = view.nearest_depth = 5.0f;
  view.scene_radius = 3.0f;
  ssao::update_for_frame(params, settings, view);
  // Radius 2 at depth 5 spans 2 * 927 / 5 = 371 pixels: level floor(log2(371 / 16)) = 4; radius 0.125: 23 pixels: level 0.
  EXPECT_EQ(params.levels[0].x, 4);
  EXPECT_EQ(params.levels[4].x, 0);
  settings.depth_chain = false;
  ssao::update_for_frame(params, settings, view);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(params.levels[k].x, 0) << "radius " << k;
}

TEST(Reference, GaussianBlurPreservesAConstantAndBilateralStopsAtDepthEdges) {
  constexpr int w = 32, h = 8;
  ssao::BlurSettings blur;
  std::vector<ssao::AoTexel> constant(w * h, ssao::AoTexel(0.25f, 0.5f));
  const auto params = ssao::pack_blur_params(blur, 0, w, h);
  for (const auto& texel : ssao::reference_blur(constant, params, ssao::Blur::gaussian)) EXPECT_NEAR(texel.x, 0.25f, 1e-3);
  // AO 1 at depth 0.2 on the left, AO 0 at depth 0.6 on the right.
  std::vector<ssao::AoTexel> edge(w * h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      edge[static_cast<size_t>(y * w + x)] = x < w / 2 ? ssao::AoTexel(1.0f, 0.2f) : ssao::AoTexel(0.0f, 0.6f);
  const auto gaussian = ssao::reference_blur(edge, params, ssao::Blur::gaussian);
  const auto bilateral = ssao::reference_blur(edge, params, ssao::Blur::bilateral);
  const size_t left = static_cast<size_t>(4 * w + w / 2 - 1), right = left + 1;
  EXPECT_LT(gaussian[left].x, 0.9f);  // the plain Gaussian bleeds across the edge
  EXPECT_GT(gaussian[right].x, 0.1f);
  EXPECT_NEAR(bilateral[left].x, 1.0f, 1e-3);  // the bilateral one does not
  EXPECT_NEAR(bilateral[right].x, 0.0f, 1e-3);
}

// A crease: one depth throughout, the normal turning by 90 degrees at the middle (the inside corner
// of two walls). Depth cannot see it, so the bilateral blur bleeds across; the denoiser's normal
// weight keeps each side's AO, at half resolution reading the normal of each texel's full pixel.
TEST(Reference, DenoiseAlsoStopsAtCreasesWhereDepthRunsOn) {
  constexpr int w = 32, h = 8;
  ssao::BlurSettings blur;
  for (int shift : {0, 1}) {
    const auto params = ssao::pack_blur_params(blur, 0, w, h, shift);
    std::vector<ssao::AoTexel> crease(w * h);
    const int full_w = w << shift, full_h = h << shift;
    std::vector<glm::vec3> normals(static_cast<size_t>(full_w * full_h));
    for (int y = 0; y < full_h; ++y)
      for (int x = 0; x < full_w; ++x)
        normals[static_cast<size_t>(y * full_w + x)] = x < full_w / 2 ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) crease[static_cast<size_t>(y * w + x)] = ssao::AoTexel(x < w / 2 ? 1.0f : 0.0f, 0.4f);
    const auto bilateral = ssao::reference_blur(crease, params, ssao::Blur::bilateral);
    const auto denoised = ssao::reference_blur(crease, params, ssao::Blur::denoise, normals, full_w);
    const size_t left = static_cast<size_t>(4 * w + w / 2 - 1), right = left + 1;
    EXPECT_LT(bilateral[left].x, 0.9f) << "shift " << shift;
    EXPECT_NEAR(denoised[left].x, 1.0f, 1e-3) << "shift " << shift;
    EXPECT_NEAR(denoised[right].x, 0.0f, 1e-3) << "shift " << shift;
    // On one face it is the bilateral blur.
    const size_t inside = static_cast<size_t>(4 * w + 4);
    EXPECT_NEAR(denoised[inside].x, bilateral[inside].x, 1e-6) << "shift " << shift;
  }
}

}  // namespace

namespace {

// Temporal accumulation turns the samples frame by frame. Frame 0 is the fixed tables; the turns of
// the first N frames fill the whole circle evenly, so that every pixel sees every direction, not
// only its own tile angle's neighbourhood (R2: the largest gap between sorted shares stays within a
// small multiple of 1/N), and every entry of the tile moves by the same angle. The kernel stays.
TEST(Frame, AdvancingTurnsTheTileEvenlyRoundTheCircleOverFrames) {
  for (ssao::Estimator estimator : ssao::kEstimators) {
    ssao::AoSettings settings;
    settings.estimator = estimator;
    const auto base = params_for(settings, 1.0f);
    auto params = base;
    ssao::advance_frame(params, 0);
    for (int i = 0; i < SSAO_ROTATION_TILE * SSAO_ROTATION_TILE; ++i) {
      EXPECT_NEAR(params.rotation[i].x, base.rotation[i].x, 1e-6f);
      EXPECT_NEAR(params.rotation[i].y, base.rotation[i].y, 1e-6f);
    }
    const double gap = 2.0 * 3.14159265358979;
    std::vector<double> shares;
    for (unsigned frame = 0; frame < 64; ++frame) {
      ssao::advance_frame(params, frame);
      double turn = 0.0;
      for (int i = 0; i < SSAO_ROTATION_TILE * SSAO_ROTATION_TILE; ++i) {
        const double a =
            std::atan2(params.rotation[i].y, params.rotation[i].x) - std::atan2(base.rotation[i].y, base.rotation[i].x);
        const double wrapped = std::remainder(a, 2.0 * 3.14159265358979);
        const double share = (wrapped < -1e-6 ? wrapped + 2.0 * 3.14159265358979 : std::max(wrapped, 0.0)) / gap;
        if (i == 0) turn = share;
        EXPECT_NEAR(share, turn, 1e-4) << "frame " << frame << ", entry " << i;
      }
      EXPECT_GE(turn, 0.0);
      EXPECT_LT(turn, 1.0 + 1e-6);
      shares.push_back(turn);
      for (int i = 0; i < params.samples; ++i) EXPECT_EQ(params.kernel[i], base.kernel[i]) << "frame " << frame;
    }
    std::sort(shares.begin(), shares.end());
    double largest = 1.0 - shares.back() + shares.front();
    for (size_t i = 1; i < shares.size(); ++i) largest = std::max(largest, shares[i] - shares[i - 1]);
    EXPECT_LE(largest, 2.5 / 64.0) << ssao::name(estimator);
  }
}

// The horizon's taps lie at the ends of their steps in a single frame (rotation[i].z = 0.5). Over
// accumulated frames each entry of the tile moves its taps along their steps through every share of
// a step evenly (the golden ratio's sequence), and in one frame the sixteen entries hold sixteen
// different shares, so neighbours do not find the same occluders at the same distances.
TEST(Frame, AdvancingMovesEachTapThroughItsWholeStepOverFrames) {
  constexpr int kEntries = SSAO_ROTATION_TILE * SSAO_ROTATION_TILE;
  ssao::AoSettings settings;
  settings.estimator = ssao::Estimator::horizon;
  auto params = params_for(settings, 1.0f);
  for (int i = 0; i < kEntries; ++i) EXPECT_EQ(params.rotation[i].z, 0.5f) << "entry " << i << " of a single frame";
  std::vector<std::vector<double>> shares(kEntries);
  for (unsigned frame = 0; frame < 64; ++frame) {
    ssao::advance_frame(params, frame);
    std::vector<double> this_frame;
    for (int i = 0; i < kEntries; ++i) {
      const double share = params.rotation[i].z;
      EXPECT_GE(share, 0.0);
      EXPECT_LT(share, 1.0);
      shares[static_cast<size_t>(i)].push_back(share);
      this_frame.push_back(share);
    }
    std::sort(this_frame.begin(), this_frame.end());
    for (size_t i = 1; i < this_frame.size(); ++i)
      EXPECT_NEAR(this_frame[i] - this_frame[i - 1], 1.0 / kEntries, 1e-5) << "frame " << frame << ": a sixteenth apart";
  }
  for (int i = 0; i < kEntries; ++i) {
    std::vector<double>& entry = shares[static_cast<size_t>(i)];
    std::sort(entry.begin(), entry.end());
    double largest = 1.0 - entry.back() + entry.front();
    for (size_t k = 1; k < entry.size(); ++k) largest = std::max(largest, entry[k] - entry[k - 1]);
    EXPECT_LE(largest, 2.5 / 64.0) << "entry " << i;
  }
}

}  // namespace

namespace {

// Accumulated over frames, the horizon's AO must not depend on how many slices each frame takes:
// a pixel's slice s turns over its own pi / slices only, so the slices must be evenly spaced for
// their turns to cover every direction once. Offset by the pattern's points, as they once were, two
// slices covered some directions twice and others never, and the accumulated AO converged on an
// error of its own for each slice count (MAE after 16 frames, six scenes: 2 slices 0.0096, 3 0.0073,
// 6 0.0069). The occluder here is one-sided (a step up to the right), so the AO depends on direction.
TEST(HorizonOverFrames, ConvergesOnTheSameAoWhateverTheSliceCount) {
  constexpr int kSteps = 4, kFrames = 64;
  std::vector<float> image(kSize * kSize, 5.0f);
  for (int y = 0; y < kSize; ++y)
    for (int x = kSize / 2; x < kSize; ++x) image[static_cast<size_t>(y * kSize + x)] = 4.7f;
  const auto accumulated = [&](int slices) {
    ssao::AoSettings settings;
    settings.estimator = ssao::Estimator::horizon;
    settings.steps = kSteps;
    settings.samples = 2 * kSteps * slices;
    auto params = params_for(settings, 0.4f);
    std::vector<double> sum(image.size(), 0.0);
    for (unsigned frame = 0; frame < kFrames; ++frame) {
      ssao::advance_frame(params, frame);
      const auto ao = run(image, params, ssao::Estimator::horizon);
      for (size_t i = 0; i < ao.size(); ++i) sum[i] += ao[i].x;
    }
    for (double& v : sum) v /= kFrames;
    return sum;
  };
  const std::vector<double> many = accumulated(8);
  double occluded = 0.0;
  for (double v : many) occluded = std::max(occluded, v);
  ASSERT_GT(occluded, 0.1) << "the step occludes the floor beside it";
  for (int slices : {2, 3, 5}) {
    const std::vector<double> few = accumulated(slices);
    double difference = 0.0, worst = 0.0;
    for (size_t i = 0; i < few.size(); ++i) {
      difference += std::abs(few[i] - many[i]);
      worst = std::max(worst, std::abs(few[i] - many[i]));
    }
    difference /= static_cast<double>(few.size());
    // Evenly spaced, 1e-4 on average and 0.011 at worst (64 frames are not yet the limit); offset by
    // the poisson points, 0.0008 to 0.0024 and 0.036 to 0.063.
    EXPECT_LE(difference, 5e-4) << slices << " slices against 8";
    EXPECT_LE(worst, 0.02) << slices << " slices against 8";
  }
}

}  // namespace
