#include "scene/camera.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace scene {

glm::dmat4 Camera::view() const {
  return glm::lookAt(eye, target, up);
}

glm::dmat4 Camera::projection() const {
  return glm::perspective(fov_y, aspect, near, far);
}

Camera frame(const Bounds& bounds, const Framing& framing, int width, int height) {
  Camera camera;
  camera.aspect = static_cast<double>(width) / static_cast<double>(height);
  camera.fov_y = glm::radians(framing.fov_y_deg);
  const double fov_x = 2.0 * std::atan(std::tan(camera.fov_y * 0.5) * camera.aspect);
  const double radius = std::max(bounds.radius(), 1e-30);
  const double fit = radius / std::sin(std::min(camera.fov_y, fov_x) * 0.5);
  const double distance = fit * framing.distance;
  const double azimuth = glm::radians(framing.azimuth_deg), elevation = glm::radians(framing.elevation_deg);
  const glm::dvec3 direction(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                             std::cos(elevation) * std::cos(azimuth));
  camera.target = bounds.centre();
  camera.eye = camera.target + distance * direction;
  // Looking straight up or down, +Y cannot be "up"; use the azimuth's forward direction instead.
  if (std::abs(direction.y) > 0.999) camera.up = glm::dvec3(-std::sin(azimuth), 0.0, -std::cos(azimuth));
  // The bounding sphere lies within [distance - radius, distance + radius]; a small margin keeps
  // its nearest and farthest points off the clip planes. Inside the sphere, near is a fraction of far.
  camera.far = (distance + radius) * 1.01;
  camera.near = std::max((distance - radius) * 0.99, camera.far * 1e-4);
  return camera;
}

Camera from_file(const FileCamera& file, const Bounds& bounds, int width, int height) {
  Camera camera;
  camera.aspect = static_cast<double>(width) / static_cast<double>(height);
  camera.fov_y = file.yfov;
  camera.eye = glm::dvec3(file.world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
  const glm::dvec3 forward = glm::dvec3(file.world * glm::dvec4(0.0, 0.0, -1.0, 0.0));
  const glm::dvec3 up = glm::dvec3(file.world * glm::dvec4(0.0, 1.0, 0.0, 0.0));
  camera.target = camera.eye + glm::normalize(forward);
  camera.up = glm::normalize(up);
  camera.near = file.znear;
  const double reach = glm::length(bounds.centre() - camera.eye) + bounds.radius();
  camera.far = file.zfar > 0.0 ? file.zfar : std::max(reach * 1.01, file.znear * 2.0);
  return camera;
}

}  // namespace scene
