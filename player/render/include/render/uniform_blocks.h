#pragma once
// The uniform blocks the render passes upload (gles_shaders/shared_layout.glsl), one pack per block:
// each fills its block from what the block is made of and nothing else, so what a shader reads can
// be traced to its source here. ssao/params.h packs the SSAO and blur blocks, which the CPU
// reference reads too.
#include "render/scene_gpu.h"
#include "render/view.h"
#include "render/view_targets.h"

#include <glm/glm.hpp>

#include <vector>

namespace render {

// temporal.comp's: this frame's view against the one the history was last computed with (the
// targets' ao_view, ao_projection, ao_far). `moved`: the view changed since the previous frame.
shared_layout::TemporalParams pack_temporal_params(const ViewTargets& targets, const View& view, bool moved);

// present.frag's, for `view` presented with its lower-left pixel at `viewport` in the framebuffer;
// `fade` multiplies the image; `scene`'s environment lights it, and the key light unless the scene
// brings lights of its own.
shared_layout::CompositeParams pack_composite_params(const ViewTargets& targets, const View& view, glm::ivec2 viewport,
                                                     float fade, const SceneGpu& scene);

// present.frag's lights: the scene's own, in world space (at most MAX_LIGHTS; the loader keeps no more).
shared_layout::LightParams pack_light_params(const std::vector<scene::Light>& lights);

// upsample.comp's (read-back only): the upsampling the last presented frame did, with its 1/far.
shared_layout::UpsampleParams pack_upsample_params(const ViewTargets& targets);

// lightfield.glsl's: the module's world-to-image transform for the G-buffer and Algorithm 2.
shared_layout::ModuleParams pack_module_params(const ModuleView& view);

// 1 / far as the shaders get it: the AO's g channel and the present pass's depths are depth / far.
inline float inverse_far(const View& view) {
  return static_cast<float>(1.0 / view.far);
}

}  // namespace render
