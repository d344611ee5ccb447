#include "render/view.h"

namespace render {

View view_of(const scene::Camera& camera) {
  View view;
  view.view = camera.view();
  view.projection = camera.projection();
  view.near = camera.near;
  view.far = camera.far;
  view.eye = camera.eye;
  return view;
}

}  // namespace render

namespace render {

View module_view(const lightfield::Module& module, const lightfield::RoiTransform& roi, double seed_cell) {
  View view;
  view.view = roi.world_to_physical();
  view.near = module.observer_distance - module.z_front;
  view.far = module.observer_distance - module.z_back;
  view.eye = roi.to_world({module.x, module.observer_height, module.z});
  view.module = ModuleView{module, roi, seed_cell};
  return view;
}

}  // namespace render
