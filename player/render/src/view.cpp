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
