#include "render/output.h"

namespace render {

bool ViewOutput::configure(const FrameSettings& settings, const SceneGpu& scene, bool srgb_target, std::string& error) {
  adjustment_.clear();
  return targets_.configure(programs_, caps_, settings, scene, srgb_target, error) &&
         prepare_material_programs(programs_, scene, targets_, srgb_target, error);
}

void ViewOutput::render(const OutputFrame& frame) {
  draw_view(context(frame));
}

void ViewOutput::present(const OutputFrame& frame, const PresentTarget& target, int, int) {
  present_pass(context(frame), target, frame.fade);
}

}  // namespace render
