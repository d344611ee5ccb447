#pragma once
// A view: where the image is seen from and how it is projected. Matrices, not eye and target, so
// off-axis projections (light field modules, quilt views, a window's sub-rectangle) fit as they are.
#include "lightfield/modules.h"
#include "scene/camera.h"

#include <glm/glm.hpp>

#include <optional>

namespace render {

// An optical module of a light field display: `view` is then the ROI's world-to-physical transform,
// `projection` is unused (the module's world-to-image transform is not a matrix), near and far are
// the module's depth range as distances from the observer line, and SSAO runs Algorithm 2.
struct ModuleView {
  lightfield::Module module;
  lightfield::RoiTransform roi;
  double seed_cell = 1.0;    // world size of the cells that share one sample turn in every module
  bool pixel_turns = false;  // turn samples by pixel tile instead (lfbench measures the difference)
};

struct View {
  glm::dmat4 view{1.0};        // world -> view space (camera at the origin, looking along -Z)
  glm::dmat4 projection{1.0};  // view -> clip; any frustum, symmetric or not
  double near = 0.1, far = 100.0;
  glm::dvec3 eye{0.0};               // the centre of projection in world space
  std::optional<ModuleView> module;  // set: a light field module (see ModuleView)
};

// The view of module `module` for a scene whose region of interest maps by `roi`.
View module_view(const lightfield::Module& module, const lightfield::RoiTransform& roi, double seed_cell);

View view_of(const scene::Camera& camera);

}  // namespace render
