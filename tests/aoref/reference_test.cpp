// Both references on analytic scenes whose AO is known in closed form, and on the player's own
// estimator. Tolerances are binomial standard errors (conservative: the sampling is stratified).
#include "aoref/reference.h"
#include "helpers.h"
#include "ssao/params.h"
#include "ssao/reference.h"

#include <glm/gtc/matrix_transform.hpp>

#include <numbers>

namespace aoref::test {
namespace {

constexpr double kPi = std::numbers::pi;

// Near-field obscurance with cosine weighting: by Malley's method the (x, y) of a cosine-weighted
// direction are uniform on the unit disk. A wall x = -a R (a in [0, 1]) is hit within R exactly when
// x <= -a, so the occluded fraction is the disk's segment beyond the chord at distance a, over pi:
// (acos a - a sqrt(1 - a^2)) / pi. It is 1/2 for a wall at the point (a = 0) and 0 at a = 1.
double wall_fraction(double a) {
  return (std::acos(a) - a * std::sqrt(1.0 - a * a)) / kPi;
}

// The disk's area with x > a and y > b (a^2 + b^2 < 1): the integral of sqrt(1 - x^2) - b over
// [a, sqrt(1 - b^2)], with the antiderivative F(x) = (x sqrt(1 - x^2) + asin x) / 2.
double quarter_cap(double a, double b) {
  const auto f = [](double x) { return 0.5 * (x * std::sqrt(1.0 - x * x) + std::asin(x)); };
  const double end = std::sqrt(1.0 - b * b);
  return f(end) - f(a) - b * (end - a);
}

// Two walls x = -a R and y = -b R: the union of both segments, so subtract the shared cap.
double corner_fraction(double a, double b) {
  return wall_fraction(a) + wall_fraction(b) - quarter_cap(a, b) / kPi;
}

ReferenceResult run(const RayScene& rays, const View& view, ReferenceSettings settings) {
  ReferenceResult result;
  std::string error;
  EXPECT_TRUE(compute_reference(rays, view, settings, result, error)) << error;
  return result;
}

// Every pixel within 5 standard errors of `expected`, and the mean of the image within 5 standard
// errors of the mean (pixels are independent estimates).
void expect_fraction(const Image& image, double expected, int rays, const char* what) {
  const double se = binomial(expected, rays);
  for (size_t i = 0; i < image.pixel_count(); ++i) ASSERT_NEAR(image.at(i), expected, 5.0 * se + 1e-6) << what << " pixel " << i;
  EXPECT_NEAR(mean(image), expected, 5.0 * se / std::sqrt(static_cast<double>(image.pixel_count())) + 1e-6) << what;
}

scene::Scene floor_scene(double half) {
  scene::Scene s;
  add_quad(s, {-half, -half, 0.0}, {2.0 * half, 0.0, 0.0}, {0.0, 2.0 * half, 0.0});
  return s;
}

TEST(NearField, OpenPlaneIsUnoccluded) {
  scene::Scene s = floor_scene(10.0);
  const RayScene rays = build(s);
  ReferenceSettings settings;
  settings.reference = Reference::near_field;
  settings.rays = 256;
  const ReferenceResult r = run(rays, uniform_view(8, 8, {0.3, -0.2, 0.0}, {0, 0, 1}, {0, 0, 5}, {1.0}), settings);
  for (size_t i = 0; i < r.ao.pixel_count(); ++i) EXPECT_EQ(r.ao.at(i), 0.0f);
  EXPECT_EQ(r.max_standard_error, 0.0);
  EXPECT_EQ(r.rays_traced, 64u * 256u);
}

class NearFieldWall : public ::testing::TestWithParam<double> {};

TEST_P(NearFieldWall, MatchesTheDiskSegment) {
  const double a = GetParam(), radius = 1.0;
  scene::Scene s = floor_scene(10.0);
  add_quad(s, {-a * radius, -10.0, 0.0}, {0.0, 20.0, 0.0}, {0.0, 0.0, 10.0});  // taller than R: its top is never missed
  const RayScene rays = build(s);
  ReferenceSettings settings;
  settings.reference = Reference::near_field;
  settings.rays = 1024;
  const ReferenceResult r = run(rays, uniform_view(16, 16, {0, 0, 0}, {0, 0, 1}, {3, 0, 3}, {radius}), settings);
  expect_fraction(r.ao, wall_fraction(a), settings.rays, "wall");
}

// a = 0.001: a wall right at the point (0.4994; exactly 0 would put the ray origins on the wall).
INSTANTIATE_TEST_SUITE_P(Distances, NearFieldWall, ::testing::Values(0.001, 0.25, 0.5, 0.9), [](const auto& param_info) {
  std::string name = "a";  // GCC 12 warns falsely on "a" + std::string&&
  name += std::to_string(static_cast<int>(param_info.param * 1000.0));
  return name + "e_3";
});

TEST(NearField, CornerOfTwoWallsMatchesTheUnionOfSegments) {
  const double a = 0.25, b = 0.4;  // corner_fraction(0.25, 0.4) = 0.5330
  scene::Scene s = floor_scene(10.0);
  add_quad(s, {-a, -10.0, 0.0}, {0.0, 20.0, 0.0}, {0.0, 0.0, 10.0});
  add_quad(s, {-10.0, -b, 0.0}, {20.0, 0.0, 0.0}, {0.0, 0.0, 10.0});
  const RayScene rays = build(s);
  ReferenceSettings settings;
  settings.reference = Reference::near_field;
  settings.rays = 1024;
  const ReferenceResult r = run(rays, uniform_view(16, 16, {0, 0, 0}, {0, 0, 1}, {3, 3, 3}, {1.0}), settings);
  expect_fraction(r.ao, corner_fraction(a, b), settings.rays, "corner");
}

TEST(NearField, InsideAClosedBoxSmallerThanTheRadiusIsFullyOccluded) {
  // Box [-0.25, 0.25]^2 x [0, 0.5], the point at the centre of its floor: the farthest wall point is
  // sqrt(0.25^2 + 0.25^2 + 0.5^2) = 0.61 away, inside R = 1, so every ray hits.
  scene::Scene s;
  add_box(s, {-0.25, -0.25, 0.0}, {0.25, 0.25, 0.5});
  const RayScene rays = build(s);
  ReferenceSettings settings;
  settings.reference = Reference::near_field;
  settings.rays = 256;
  const ReferenceResult r = run(rays, uniform_view(8, 8, {0, 0, 0}, {0, 0, 1}, {5, 5, 5}, {0.1}), settings);
  EXPECT_EQ(r.ao.at(0), 0.0f) << "R = 0.1 from the view reaches no wall";
  settings.radius = 1.0;  // the override replaces the view's radius
  const ReferenceResult full = run(rays, uniform_view(8, 8, {0, 0, 0}, {0, 0, 1}, {5, 5, 5}, {0.1}), settings);
  for (size_t i = 0; i < full.ao.pixel_count(); ++i) EXPECT_EQ(full.ao.at(i), 1.0f);
}

TEST(NearField, SceneFarFromTheOriginKeepsItsAccuracy) {
  // The wall at a = 0.5 translated by 1e4 through the instance matrices: the BVH stores coordinates
  // relative to the scene's centre, so only the view's float positions (exact here) could lose digits.
  const glm::dmat4 far = glm::translate(glm::dmat4(1.0), glm::dvec3(1e4, -1e4, 1e4));
  scene::Scene s;
  add_quad(s, {-10.0, -10.0, 0.0}, {20.0, 0.0, 0.0}, {0.0, 20.0, 0.0}, far);
  add_quad(s, {-0.5, -10.0, 0.0}, {0.0, 20.0, 0.0}, {0.0, 0.0, 10.0}, far);
  const RayScene rays = build(s);
  ReferenceSettings settings;
  settings.reference = Reference::near_field;
  settings.rays = 1024;
  const ReferenceResult r = run(rays, uniform_view(8, 8, {1e4, -1e4, 1e4}, {0, 0, 1}, {1e4 + 3, -1e4, 1e4 + 3}, {1.0}), settings);
  expect_fraction(r.ao, wall_fraction(0.5), settings.rays, "translated wall");
}

class SphereOnPlane : public ::testing::TestWithParam<glm::dvec3> {};

TEST_P(SphereOnPlane, HidesHalfTheShellForEveryRadius) {
  // A point on a plane seen from anywhere in front of it: the hidden part of the shell is exactly the
  // half behind the plane, for every radius, so the merged value is 1/2 up to the max of noisy estimates.
  scene::Scene s = floor_scene(50.0);
  const RayScene rays = build(s);
  ReferenceSettings settings;
  settings.rays = 1024;
  const std::vector<double> radii{1.0, 0.5, 0.25};
  const ReferenceResult r = run(rays, uniform_view(16, 16, {0.2, 0.1, 0.0}, {0, 0, 1}, GetParam(), radii), settings);
  ASSERT_EQ(r.per_radius.size(), radii.size());
  for (const Image& image : r.per_radius) expect_fraction(image, 0.5, settings.rays, "per radius");
  for (size_t i = 0; i < r.ao.pixel_count(); ++i) {
    float merged = 0.0f;
    for (const Image& image : r.per_radius) merged = std::max(merged, image.at(i));
    ASSERT_EQ(r.ao.at(i), merged);
  }
  EXPECT_NEAR(mean(r.ao), 0.5, 4.0 * binomial(0.5, settings.rays));
  EXPECT_EQ(r.rays_traced, 256u * 1024u * 3u);
}

INSTANTIATE_TEST_SUITE_P(Eyes, SphereOnPlane, ::testing::Values(glm::dvec3(0, 0, 10), glm::dvec3(6, -3, 2)),
                         [](const auto& param_info) { return std::string(param_info.param.x == 0.0 ? "Above" : "Oblique"); });

class SphereVsPlayer : public ::testing::TestWithParam<ssao::Pattern> {};

TEST_P(SphereVsPlayer, AgreesOnAFacingPlane) {
  // The player's CPU reference of ssao.comp on a plane at depth 5 facing the camera, and the
  // ray-traced sphere reference at the same reconstructed points (camera at the origin looking down -Z).
  constexpr int kSize = 48;
  const double depth = 5.0;
  const glm::mat4 projection = glm::perspective(glm::radians(45.0f), 1.0f, 0.5f, 20.0f);
  ssao::AoSettings ao;
  ao.estimator = ssao::Estimator::sphere;
  ao.radii = 5;
  ao.samples = 64;
  ao.pattern = GetParam();
  ao.half_resolution = false;  // the player's AO at every pixel the ray tracer sees
  const float radius = 0.3f;
  auto params = ssao::pack_ssao_params(ao, radius, kSize, kSize);
  ssao::FrameView frame;
  frame.projection = projection;
  frame.nearest_depth = frame.centre_depth = static_cast<float>(depth);
  frame.scene_radius = 50.0f;
  ao.skip_radii = false;  // every radius computed, so the comparison is with the full estimator
  ssao::update_for_frame(params, ao, frame);
  const std::vector<float> depth_image(kSize * kSize, static_cast<float>(depth));
  const std::vector<glm::vec3> facing(depth_image.size(), glm::vec3(0, 0, 1));
  const auto player = ssao::reference_ssao(ssao::build_depth_chain(depth_image, kSize, kSize), facing, {}, params, 1.0f / 20.0f,
                                           ssao::Estimator::sphere);

  scene::Scene s;
  add_quad(s, {-50.0, -50.0, -depth}, {100.0, 0.0, 0.0}, {0.0, 100.0, 0.0});
  const RayScene rays = build(s);
  View view = uniform_view(kSize, kSize, {0, 0, -depth}, {0, 0, 1}, {0, 0, 0}, {});
  for (int row = 0; row < kSize; ++row)  // row 0 at the top, as in the dump
    for (int x = 0; x < kSize; ++x) {
      const size_t i = static_cast<size_t>(row * kSize + x);
      const double ndc_x = (x + 0.5) / kSize * 2.0 - 1.0, ndc_y = 1.0 - (row + 0.5) / kSize * 2.0;
      view.position.at(i, 0) = static_cast<float>(ndc_x * depth / projection[0][0]);
      view.position.at(i, 1) = static_cast<float>(ndc_y * depth / projection[1][1]);
    }
  for (int k = 0; k < params.radius_count; ++k) view.radii.push_back(params.radii[k].x);
  ReferenceSettings settings;
  settings.rays = 256;
  const ReferenceResult r = run(rays, view, settings);

  // Interior only: the largest radius spans 0.3 / (5 tan 22.5 deg) * 24 = 3.5 px, and the player
  // counts nothing for samples that leave the frame.
  double player_sum = 0.0, reference_sum = 0.0;
  int n = 0;
  for (int y = 6; y < kSize - 6; ++y)
    for (int x = 6; x < kSize - 6; ++x, ++n) {
      player_sum += player[static_cast<size_t>(y * kSize + x)].x;
      reference_sum += r.ao.at(static_cast<size_t>(y * kSize + x));
    }
  const double player_mean = player_sum / n, reference_mean = reference_sum / n;
  EXPECT_NEAR(reference_mean, 0.5, 4.0 * binomial(0.5, settings.rays));
  // On a plane the estimator returns its kernel's share of samples farther than the depth bias
  // behind the plane, for every pixel (the turn about the view axis leaves z alone): 28/64 = 0.4375
  // for the Poisson kernel, 30/64 random, 31/64 jittered and Latin, against the exact 1/2. The bias
  // alone removes about 1.5% of the shell (3% of R, and a thin shell's z is uniform).
  EXPECT_NEAR(player_mean, reference_mean, 0.07);
  EXPECT_LE(player_mean, reference_mean + 1.0 / 64.0) << "the bias can only remove hidden samples";
}

INSTANTIATE_TEST_SUITE_P(AllPatterns, SphereVsPlayer,
                         ::testing::Values(ssao::Pattern::random, ssao::Pattern::jittered, ssao::Pattern::latin,
                                           ssao::Pattern::poisson),
                         [](const auto& param_info) { return std::string(ssao::name(param_info.param)); });

TEST(Reference, IsReproducibleAndIndependentOfThreadCount) {
  scene::Scene s = floor_scene(10.0);
  add_quad(s, {-0.3, -10.0, 0.0}, {0.0, 20.0, 0.0}, {0.0, 0.0, 10.0});
  const RayScene rays = build(s);
  const View view = uniform_view(8, 8, {0, 0, 0}, {0, 0, 1}, {4, 1, 3}, {1.0, 0.5});
  for (Reference kind : {Reference::near_field, Reference::sphere}) {
    ReferenceSettings settings;
    settings.reference = kind;
    settings.rays = 64;
    settings.threads = 1;
    const ReferenceResult one = run(rays, view, settings);
    settings.threads = 3;
    const ReferenceResult three = run(rays, view, settings);
    EXPECT_EQ(one.ao.values, three.ao.values) << name(kind);
    settings.seed = 2;
    const ReferenceResult other = run(rays, view, settings);
    EXPECT_NE(one.ao.values, other.ao.values) << name(kind) << ": the seed must change the samples";
  }
}

TEST(Reference, BackgroundStaysZeroAndProgressReachesTheEnd) {
  scene::Scene s = floor_scene(10.0);
  add_quad(s, {-0.3, -10.0, 0.0}, {0.0, 20.0, 0.0}, {0.0, 0.0, 10.0});
  const RayScene rays = build(s);
  View view = uniform_view(6, 5, {0, 0, 0}, {0, 0, 1}, {4, 1, 3}, {1.0});
  for (size_t i = 0; i < view.position.pixel_count(); i += 2) view.position.at(i, 3) = view.normal.at(i, 3) = 0.0f;
  ReferenceSettings settings;
  settings.rays = 32;
  int last_done = -1, last_total = -1;
  settings.progress = [&](int done, int total) { last_done = done, last_total = total; };
  const ReferenceResult r = run(rays, view, settings);
  EXPECT_EQ(last_done, 5);
  EXPECT_EQ(last_total, 5);
  EXPECT_EQ(r.object_pixels, 15u);
  for (size_t i = 0; i < r.ao.pixel_count(); i += 2) {
    EXPECT_EQ(r.ao.at(i), 0.0f);
    EXPECT_EQ(r.standard_error.at(i), 0.0f);
  }
  for (size_t i = 1; i < r.ao.pixel_count(); i += 2) EXPECT_GT(r.ao.at(i), 0.0f);
}

TEST(Reference, RejectsBadSettingsWithTheFieldName) {
  scene::Scene s = floor_scene(1.0);
  const RayScene rays = build(s);
  const View view = uniform_view(2, 2, {0, 0, 0}, {0, 0, 1}, {0, 0, 3}, {1.0});
  ReferenceResult result;
  std::string error;
  ReferenceSettings settings;
  settings.rays = 0;
  EXPECT_FALSE(compute_reference(rays, view, settings, result, error));
  EXPECT_NE(error.find("rays"), std::string::npos) << error;
  settings.rays = 8;
  settings.radius = -1.0;
  EXPECT_FALSE(compute_reference(rays, view, settings, result, error));
  EXPECT_NE(error.find("radius"), std::string::npos) << error;
  settings.radius = 0.0;
  View no_radii = view;
  no_radii.radii.clear();
  EXPECT_FALSE(compute_reference(rays, no_radii, settings, result, error));
  EXPECT_NE(error.find("radii"), std::string::npos) << error;
  EXPECT_FALSE(compute_reference(RayScene(), view, settings, result, error));
  EXPECT_NE(error.find("scene"), std::string::npos) << error;
}

TEST(RayScene, DropsDegenerateTrianglesAndAppliesTransforms) {
  scene::Scene s;
  scene::Mesh mesh;
  const glm::vec3 n(0, 0, 1);
  mesh.vertices = {{{0, 0, 0}, n, {}}, {{1, 0, 0}, n, {}}, {{0, 1, 0}, n, {}}, {{2, 0, 0}, n, {}}};
  // One real triangle, one with a repeated vertex, one with collinear vertices.
  mesh.indices = {0, 1, 2, 0, 0, 1, 0, 1, 3};
  s.meshes.push_back(mesh);
  s.instances.push_back({0, glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, 2))});
  const RayScene rays = build(s);
  EXPECT_EQ(rays.triangle_count(), 1u);
  EXPECT_EQ(rays.skipped_triangles(), 2u);
  EXPECT_TRUE(rays.occluded({0.2, 0.2, 0.0}, {0, 0, 1}, 0.0, 3.0)) << "the triangle was moved to z = 2";
  EXPECT_FALSE(rays.occluded({0.2, 0.2, 0.0}, {0, 0, 1}, 0.0, 1.9)) << "t_far stops short of it";
  EXPECT_FALSE(rays.occluded({0.8, 0.8, 0.0}, {0, 0, 1}, 0.0, 3.0)) << "outside the triangle";

  scene::Scene empty;
  mesh.indices = {0, 0, 1};
  empty.meshes.push_back(mesh);
  empty.instances.push_back({0, glm::dmat4(1.0)});
  scene::update_bounds(empty);
  RayScene nothing;
  std::string error;
  EXPECT_FALSE(nothing.build(empty, error));
  EXPECT_NE(error.find("non-zero area"), std::string::npos) << error;
}

}  // namespace
}  // namespace aoref::test
