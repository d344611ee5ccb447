#pragma once
// Scenes and views with known AO, built in code, shared by the aoref tests.
#include "aoref/dump.h"
#include "aoref/ray_scene.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace aoref::test {

// A quad corner + s u + t v (s, t in [0, 1]) as two triangles, placed by `world`.
inline void add_quad(scene::Scene& s, glm::dvec3 corner, glm::dvec3 u, glm::dvec3 v, glm::dmat4 world = glm::dmat4(1.0)) {
  scene::Mesh mesh;
  const glm::vec3 n = glm::normalize(glm::cross(glm::vec3(u), glm::vec3(v)));
  for (const glm::dvec3& p : {corner, corner + u, corner + u + v, corner + v})
    mesh.vertices.push_back({glm::vec3(p), n, glm::vec2(0.0f)});
  mesh.indices = {0, 1, 2, 0, 2, 3};
  s.meshes.push_back(mesh);
  s.instances.push_back({static_cast<int>(s.meshes.size()) - 1, world});
}

// The closed axis-aligned box [lo, hi] as six quads.
inline void add_box(scene::Scene& s, glm::dvec3 lo, glm::dvec3 hi) {
  const glm::dvec3 d = hi - lo;
  const glm::dvec3 x(d.x, 0, 0), y(0, d.y, 0), z(0, 0, d.z);
  add_quad(s, lo, y, x);
  add_quad(s, lo + z, x, y);
  add_quad(s, lo, x, z);
  add_quad(s, lo + y, z, x);
  add_quad(s, lo, z, y);
  add_quad(s, lo + x, y, z);
}

inline RayScene build(scene::Scene& s) {
  s.materials = {scene::Material{}};
  scene::update_bounds(s);
  RayScene rays;
  std::string error;
  EXPECT_TRUE(rays.build(s, error)) << error;
  return rays;
}

// A w x h view in which every pixel is the same surface point: each pixel is then an independent
// estimate (its own seed), which the tests average and bound.
inline View uniform_view(int w, int h, glm::dvec3 point, glm::dvec3 normal, glm::dvec3 eye, std::vector<double> radii) {
  View view;
  view.eye = eye;
  view.radii = std::move(radii);
  view.position = Image(w, h, 4);
  view.normal = Image(w, h, 4);
  for (size_t i = 0; i < view.position.pixel_count(); ++i)
    for (int c = 0; c < 3; ++c) {
      view.position.at(i, c) = static_cast<float>(point[c]);
      view.normal.at(i, c) = static_cast<float>(normal[c]);
      view.position.at(i, 3) = view.normal.at(i, 3) = 1.0f;
    }
  return view;
}

// Binomial standard error of a fraction p estimated from n independent rays. Stratified sampling only
// lowers the true error, so bounds built on it are conservative.
inline double binomial(double p, double n) {
  return std::sqrt(std::max(p * (1.0 - p), 0.0) / n);
}

inline double mean(const Image& image) {
  double sum = 0.0;
  for (size_t i = 0; i < image.pixel_count(); ++i) sum += image.at(i);
  return sum / static_cast<double>(image.pixel_count());
}

}  // namespace aoref::test
