#include "scene/camera.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace {

TEST(Camera, FramesTheWholeBoundingBoxWithNearAndFarAroundIt) {
  const scene::Bounds bounds{{-3.0, 10.0, 1000.0}, {5.0, 12.0, 1004.0}};
  for (double azimuth : {0.0, 45.0, 200.0})
    for (double elevation : {-30.0, 0.0, 20.0, 89.0, 90.0}) {
      scene::Framing framing;
      framing.azimuth_deg = azimuth;
      framing.elevation_deg = elevation;
      const scene::Camera camera = scene::frame(bounds, framing, 160, 90);
      const glm::dmat4 clip = camera.projection() * camera.view();
      for (int corner = 0; corner < 8; ++corner) {
        const glm::dvec4 p(corner & 1 ? bounds.max.x : bounds.min.x, corner & 2 ? bounds.max.y : bounds.min.y,
                           corner & 4 ? bounds.max.z : bounds.min.z, 1.0);
        const glm::dvec4 c = clip * p;
        ASSERT_GT(c.w, 0.0);
        EXPECT_LE(std::abs(c.x / c.w), 1.0) << azimuth << "/" << elevation;
        EXPECT_LE(std::abs(c.y / c.w), 1.0) << azimuth << "/" << elevation;
        EXPECT_GT(c.z / c.w, -1.0);
        EXPECT_LT(c.z / c.w, 1.0);
      }
      EXPECT_GT(camera.near, 0.0);
    }
}

// How the bounding sphere of `bounds` lands in `camera`'s view, from points spread over the sphere:
// the largest |x| and |y| in normalised device coordinates and the nearest and farthest eye depths.
struct SphereInView {
  double max_x = 0.0, max_y = 0.0, nearest = 1e300, farthest = 0.0;
};
SphereInView sphere_in_view(const scene::Bounds& bounds, const scene::Camera& camera) {
  const glm::dmat4 view = camera.view(), projection = camera.projection();
  SphereInView seen;
  // 360 x 181 directions: a sampled maximum falls short of the true one by about (step)^2 / 2 = 1.5e-4 of it.
  constexpr int kTurns = 360, kRings = 180;
  for (int ring = 0; ring <= kRings; ++ring)
    for (int turn = 0; turn < kTurns; ++turn) {
      const double theta = M_PI * ring / kRings, phi = 2.0 * M_PI * turn / kTurns;
      const glm::dvec3 direction(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      const glm::dvec4 eye_space = view * glm::dvec4(bounds.centre() + bounds.radius() * direction, 1.0);
      const glm::dvec4 clip = projection * eye_space;
      seen.max_x = std::max(seen.max_x, std::abs(clip.x / clip.w));
      seen.max_y = std::max(seen.max_y, std::abs(clip.y / clip.w));
      seen.nearest = std::min(seen.nearest, -eye_space.z);
      seen.farthest = std::max(seen.farthest, -eye_space.z);
    }
  return seen;
}

TEST(Camera, TheBoundingSphereFillsTheNarrowerSideOfTheView) {
  // Framing is the distance at which the bounding sphere just fits: it touches the frustum's sides
  // along the narrower field of view and stays inside the other. A camera twice too far shows it at
  // about half that size; one too near cuts it. Near and far hug the sphere's depth range (within
  // the 1% margins the framing keeps off the clip planes, and 2% here).
  const scene::Bounds bounds{{-3.0, 10.0, 1000.0}, {5.0, 12.0, 1004.0}};
  for (const auto& [width, height] : {std::pair{160, 90}, std::pair{90, 160}, std::pair{100, 100}})
    for (double azimuth : {0.0, 45.0, 200.0})
      for (double elevation : {-30.0, 0.0, 20.0, 90.0}) {
        scene::Framing framing;
        framing.azimuth_deg = azimuth;
        framing.elevation_deg = elevation;
        const scene::Camera camera = scene::frame(bounds, framing, width, height);
        const SphereInView seen = sphere_in_view(bounds, camera);
        const double narrow = width >= height ? seen.max_y : seen.max_x, wide = width >= height ? seen.max_x : seen.max_y;
        const std::string where = std::to_string(width) + "x" + std::to_string(height) + " " + std::to_string(azimuth) + "/" +
                                  std::to_string(elevation);
        EXPECT_LE(narrow, 1.0 + 1e-9) << where;
        EXPECT_GE(narrow, 1.0 - 1e-3) << where;
        EXPECT_LE(wide, 1.0 + 1e-9) << where;
        // The sphere spans the same angle both ways, so the wider side shows it at the aspect ratio's share.
        EXPECT_NEAR(wide, std::min(double(width) / height, double(height) / width), 1e-3) << where;
        EXPECT_LE(camera.near, seen.nearest) << where;
        EXPECT_GE(camera.near, 0.98 * seen.nearest) << where;
        EXPECT_GE(camera.far, seen.farthest) << where;
        EXPECT_LE(camera.far, 1.02 * seen.farthest) << where;
      }
}

TEST(Camera, DistanceFactorMovesTheEyeAlongTheSameDirection) {
  const scene::Bounds bounds{{-1.0, -1.0, -1.0}, {1.0, 1.0, 1.0}};
  scene::Framing near_framing, far_framing;
  far_framing.distance = 2.0;
  const auto a = scene::frame(bounds, near_framing, 100, 100), b = scene::frame(bounds, far_framing, 100, 100);
  EXPECT_NEAR(glm::length(b.eye - b.target), 2.0 * glm::length(a.eye - a.target), 1e-9);
  EXPECT_NEAR(glm::dot(glm::normalize(a.eye - a.target), glm::normalize(b.eye - b.target)), 1.0, 1e-12);
  // Inside the bounding sphere near stays positive.
  scene::Framing inside;
  inside.distance = 0.1;
  EXPECT_GT(scene::frame(bounds, inside, 100, 100).near, 0.0);
}

}  // namespace

// A file camera looks along its node's -Z with +Y up: its view matrix is the inverse of its node's
// world transform (rigid), whatever the surface; far reaches past the scene when zfar is absent.
TEST(Camera, AFileCameraViewsFromItsNode) {
  scene::FileCamera file;
  file.world = glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(3, -2, 7)), 0.7, glm::normalize(glm::dvec3(1, 2, -0.5)));
  file.yfov = 0.6;
  file.znear = 0.05;
  scene::Bounds bounds;
  bounds.min = glm::dvec3(-1);
  bounds.max = glm::dvec3(1);
  const scene::Camera camera = scene::from_file(file, bounds, 200, 100);
  const glm::dmat4 expected = glm::inverse(file.world), view = camera.view();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(view[c][r], expected[c][r], 1e-9) << c << "," << r;
  EXPECT_DOUBLE_EQ(camera.fov_y, 0.6);
  EXPECT_DOUBLE_EQ(camera.aspect, 2.0);
  EXPECT_DOUBLE_EQ(camera.near, 0.05);
  EXPECT_GT(camera.far, glm::length(camera.eye) + bounds.radius());
  file.zfar = 40.0;
  EXPECT_DOUBLE_EQ(scene::from_file(file, bounds, 200, 100).far, 40.0);
}
