#include "scene/camera.h"

#include <gtest/gtest.h>

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
