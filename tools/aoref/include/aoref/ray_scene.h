#pragma once
// A scene::Scene as an Embree BVH for occlusion queries. Every instance's transform is applied in
// double and the result stored as float relative to the centre of the vertices' bounds, so a scene far
// from the origin keeps the precision of its own size. Move-only; queries are thread-safe once built.
#include "scene/scene.h"

#include <glm/glm.hpp>

#include <memory>
#include <string>

namespace aoref {

class RayScene {
 public:
  RayScene();
  ~RayScene();
  RayScene(RayScene&&) noexcept;
  RayScene& operator=(RayScene&&) noexcept;
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  // Replaces any earlier contents. Zero-area and non-finite triangles are dropped (counted in
  // skipped_triangles()). Returns false and says why when Embree fails or nothing is left to hit.
  bool build(const scene::Scene& scene, std::string& error);

  // True when a triangle lies on the segment origin + t * direction, t in [t_near, t_far]. World
  // coordinates; `direction` need not be unit length (t is in its units).
  bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_near, double t_far) const;

  size_t triangle_count() const;     // triangles in the BVH
  size_t skipped_triangles() const;  // degenerate ones left out
  double scene_radius() const;       // half the diagonal of the vertices' bounds, for scale-relative epsilons

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace aoref
