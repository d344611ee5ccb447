#pragma once
// A camera that frames a scene from its bounds, with near and far fitted to them.
#include "scene/scene.h"

namespace scene {

struct Framing {
  double azimuth_deg = 30.0;    // about +Y, 0 looks along -Z
  double elevation_deg = 20.0;  // above the horizontal
  double distance = 1.0;        // multiple of the distance at which the bounding sphere just fits
  double fov_y_deg = 45.0;
};

struct Camera {
  glm::dvec3 eye{0.0}, target{0.0}, up{0.0, 1.0, 0.0};
  double fov_y = 0.0;  // radians
  double aspect = 1.0;
  double near = 0.1, far = 100.0;
  glm::dmat4 view() const;
  glm::dmat4 projection() const;
};

Camera frame(const Bounds& bounds, const Framing& framing, int width, int height);

// The view of a perspective file camera on a `width` x `height` surface (its aspect, not the
// file's: the surface is what is shown). Without a zfar, far reaches past the scene's bounds.
Camera from_file(const FileCamera& file, const Bounds& bounds, int width, int height);

}  // namespace scene
