#include "lightfield/quilt.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace lightfield {

Interleave interleave_of(const Calibration& c, int views) {
  Interleave i;
  i.pitch = c.pitch * c.screen_width / c.dpi * std::cos(std::atan(1.0 / c.slope));
  i.tilt = c.screen_height / (c.screen_width * c.slope) * (c.flip_x ? -1.0 : 1.0);
  i.subpixel = 1.0 / (3.0 * c.screen_width);
  i.center = c.center;
  i.inverted_views = c.inverted_views;
  i.views = views;
  return i;
}

double view_fraction(const Interleave& i, const Calibration& c, int x, int y, int channel) {
  const double u = (x + 0.5) / c.screen_width, v = (y + 0.5) / c.screen_height;
  const double phase = (u + channel * i.subpixel + v * i.tilt) * i.pitch - i.center;
  const double z = phase - std::floor(phase);
  return i.inverted_views ? 1.0 - z : z;
}

int view_of_subpixel(const Interleave& i, const Calibration& c, int x, int y, int channel) {
  const double z = view_fraction(i, c, x, y, channel);
  if (!(z >= 0.0 && z <= 1.0)) return 0;  // a phase too large for a double's fraction: no view is better
  return std::clamp(static_cast<int>(std::floor(z * i.views)), 0, i.views - 1);
}

glm::ivec2 tile_of(const QuiltDisplay& quilt, int view) {
  return {view % quilt.columns, view / quilt.columns};
}

OffAxisView quilt_view(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up, double fov_y, double aspect,
                       double near, double far, double view_cone_deg, int view, int views) {
  const glm::dvec3 forward = glm::normalize(target - eye);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, up));
  const double focus = glm::length(target - eye);
  const double angle = views > 1 ? (static_cast<double>(view) / (views - 1) - 0.5) * glm::radians(view_cone_deg) : 0.0;
  const double shift = focus * std::tan(angle);
  OffAxisView out;
  out.eye = eye + right * shift;
  out.view = glm::lookAt(out.eye, out.eye + forward, up);
  const double half_height = near * std::tan(fov_y * 0.5), half_width = half_height * aspect;
  // The window at the focal plane stays put: at the near plane it moves by -shift * near / focus.
  const double offset = -shift * near / focus;
  out.projection = glm::frustum(-half_width + offset, half_width + offset, -half_height, half_height, near, far);
  return out;
}

}  // namespace lightfield
