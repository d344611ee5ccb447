#pragma once
// A view: where the image is seen from and how it is projected. Matrices, not eye and target, so
// off-axis projections (light field modules, quilt views, a window's sub-rectangle) fit as they are.
#include "scene/camera.h"

#include <glm/glm.hpp>

namespace render {

struct View {
  glm::dmat4 view{1.0};        // world -> view space (camera at the origin, looking along -Z)
  glm::dmat4 projection{1.0};  // view -> clip; any frustum, symmetric or not
  double near = 0.1, far = 100.0;
  glm::dvec3 eye{0.0};         // the centre of projection in world space
};

View view_of(const scene::Camera& camera);

}  // namespace render
