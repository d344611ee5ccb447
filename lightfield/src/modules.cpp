#include "lightfield/modules.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lightfield {

glm::dmat4 RoiTransform::world_to_physical() const {
  glm::dmat4 m(scale);
  m[3] = glm::dvec4(offset, 1.0);
  return m;
}

glm::dmat4 RoiTransform::physical_to_world() const {
  glm::dmat4 m(1.0 / scale);
  m[3] = glm::dvec4(-offset / scale, 1.0);
  return m;
}

std::optional<RoiTransform> roi_transform(const Box& world, const Box& physical) {
  const glm::dvec3 world_size = world.max - world.min, physical_size = physical.max - physical.min;
  for (int axis = 0; axis < 3; ++axis)
    if (!(world_size[axis] > 0.0) || !(physical_size[axis] > 0.0) || !std::isfinite(world_size[axis]) ||
        !std::isfinite(physical_size[axis]))
      return std::nullopt;
  RoiTransform t;
  t.scale = std::min({physical_size.x / world_size.x, physical_size.y / world_size.y, physical_size.z / world_size.z});
  t.offset = (physical.min + physical.max) * 0.5 - (world.min + world.max) * 0.5 * t.scale;
  return t;
}

Box world_roi(const ModulesDisplay& display, const Box& scene_bounds) {
  if (display.world_roi) return *display.world_roi;
  const glm::dvec3 size = scene_bounds.max - scene_bounds.min;
  const double thinnest = std::max({size.x, size.y, size.z, 1e-6}) * 1e-3;
  Box box = scene_bounds;
  for (int axis = 0; axis < 3; ++axis)
    if (size[axis] < thinnest) {
      box.min[axis] -= thinnest * 0.5;
      box.max[axis] += thinnest * 0.5;
    }
  return box;
}

Module module_of(const ModulesDisplay& display, int k) {
  Module m;
  m.x = display.module_x[static_cast<size_t>(k)];
  m.z = display.module_z;
  m.observer_distance = display.observer_distance;
  m.observer_height = display.observer_height;
  m.screen_height = display.screen_height;
  m.footprint0 = display.footprint.x;
  m.footprint1 = display.footprint.y;
  m.width = display.width;
  m.height = display.height;
  const double depth = display.physical_roi.max.z - display.physical_roi.min.z;
  // 2% of the module-to-observer distance from either end keeps both perspectives' denominators away
  // from zero, where a vertex would land at infinity.
  const double margin = 0.02 * (m.observer_distance - m.z);
  m.z_back = std::max(display.physical_roi.min.z - depth, m.z + margin);
  m.z_front = std::min(display.physical_roi.max.z + depth, m.observer_distance - margin);
  return m;
}

glm::dvec2 screen_point(const Module& m, const glm::dvec3& q) {
  const double d = m.observer_distance;
  return {m.x + (q.x - m.x) * (-m.z) / (q.z - m.z), m.observer_height + (q.y - m.observer_height) * d / (d - q.z)};
}

namespace {

bool defined_at(const Module& m, const glm::dvec3& q) {
  return q.z > m.z && q.z < m.observer_distance;
}

glm::dvec2 image_of_screen(const Module& m, const glm::dvec2& s) {
  return {(s.x - m.footprint0) / (m.footprint1 - m.footprint0) * m.width,
          (m.screen_height * 0.5 - s.y) / m.screen_height * m.height};
}

}  // namespace

std::optional<glm::dvec3> physical_to_image(const Module& m, const glm::dvec3& q) {
  if (!defined_at(m, q)) return std::nullopt;
  const glm::dvec2 uv = image_of_screen(m, screen_point(m, q));
  return glm::dvec3(uv, q.z);
}

glm::dvec3 screen_point_of_pixel(const Module& m, double u, double v) {
  return {m.footprint0 + u / m.width * (m.footprint1 - m.footprint0), m.screen_height * 0.5 - v / m.height * m.screen_height,
          0.0};
}

glm::dvec3 observer_point(const Module& m, const glm::dvec3& screen) {
  return {screen.x - (screen.x - m.x) * m.observer_distance / m.z, m.observer_height, m.observer_distance};
}

glm::dvec4 clip_position(const Module& m, const glm::dvec3& q) {
  const double w = (q.z - m.z) / -m.z;
  const double d = m.observer_distance;
  const double sx = m.x + (q.x - m.x) / w;
  const double sy = m.observer_height + (q.y - m.observer_height) * d / std::max(d - q.z, 1e-6 * d);
  const glm::dvec3 ndc((sx - m.footprint0) / (m.footprint1 - m.footprint0) * 2.0 - 1.0, sy / m.screen_height * 2.0,
                       (m.z_front - q.z) / (m.z_front - m.z_back) * 2.0 - 1.0);
  return {ndc * w, w};
}

double edge_error_pixels(const Module& m, const glm::dvec3& a, const glm::dvec3& b) {
  const glm::dvec4 clip_a = clip_position(m, a), clip_b = clip_position(m, b);
  double worst = 0.0;
  constexpr int kSteps = 16;  // the error along an edge is one smooth bump: 16 samples find its top within a few percent
  for (int step = 1; step < kSteps; ++step) {
    const double t = static_cast<double>(step) / kSteps;
    const glm::dvec3 q = a + t * (b - a);
    const std::optional<glm::dvec3> exact = physical_to_image(m, q);
    // Behind the module or past the observer the module shows no point to compare with. Where it does,
    // the interpolated clip w is the point's own, which is positive in front of the module.
    if (!exact) continue;
    const glm::dvec4 clip = clip_a + t * (clip_b - clip_a);
    const glm::dvec2 drawn((clip.x / clip.w * 0.5 + 0.5) * m.width, (0.5 - clip.y / clip.w * 0.5) * m.height);
    worst = std::max(worst, glm::length(drawn - glm::dvec2(exact.value())));
  }
  return worst;
}

bool sees(const Module& m, const Box& box) {
  const double z0 = std::max(box.min.z, m.z_back), z1 = std::min(box.max.z, m.z_front);
  if (z0 > z1) return false;
  double x_low = std::numeric_limits<double>::infinity(), x_high = -x_low, y_low = x_low, y_high = -x_low;
  for (const double z : {z0, z1})
    for (const glm::dvec3& corner : {box.min, box.max}) {
      const glm::dvec2 s = screen_point(m, {corner.x, corner.y, z});
      x_low = std::min(x_low, s.x);
      x_high = std::max(x_high, s.x);
      y_low = std::min(y_low, s.y);
      y_high = std::max(y_high, s.y);
    }
  return x_high >= m.footprint0 && x_low <= m.footprint1 && y_high >= -m.screen_height * 0.5 && y_low <= m.screen_height * 0.5;
}

glm::ivec2 montage_grid(int count) {
  const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
  return {columns, (count + columns - 1) / columns};
}

}  // namespace lightfield
