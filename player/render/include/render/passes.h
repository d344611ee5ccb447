#pragma once
// The frame, one function per pass. Each records into the view's targets; none allocates, throws
// or waits on the GPU. A GL error is recorded by the PassContext, not raised.
#include "gl/frame_timer.h"
#include "render/programs.h"
#include "render/scene_gpu.h"
#include "render/view.h"
#include "render/view_targets.h"

#include <cstdint>
#include <string>
#include <string_view>

namespace render {

// The passes of one frame of one view, in order; their times are kept by index (PassTimes).
enum class Pass : std::uint8_t { depth_prepass, gbuffer, depth_chain, ssao, temporal, blur_h, blur_v, present, blend };
inline constexpr int kPassCount = static_cast<int>(Pass::blend) + 1;
std::string_view pass_name(Pass pass);

// Where the present pass writes: a framebuffer (0: the platform's), the view's rectangle in it, and
// whether the framebuffer encodes sRGB on write.
struct PresentTarget {
  unsigned framebuffer = 0;
  int x = 0, y = 0;
  bool srgb = false;
};

// What every pass of one frame of one view shares.
struct PassContext {
  Programs& programs;
  const SceneGpu& scene;
  ViewTargets& targets;
  const View& view;
  gl::FrameTimer* timer = nullptr;    // null: untimed
  std::string* gl_error = nullptr;    // the first GL error of the frame, when settings.check_errors
  void finish_pass(Pass pass) const;  // error check and timer mark
  // A draw skipped for want of its program (prepare_material_programs was not run for this
  // scene): kept as the frame's error, so it shows in the status rather than as a missing part.
  void report_missing_program(const char* what) const {
    if (gl_error != nullptr && gl_error->empty()) *gl_error = what;
  }
};

// Whether a view of `scene` with `settings` follows each pixel's motion in its temporal pass: an
// animated scene's, with temporal accumulation and motion vectors on, on a GPU with five draw
// buffers; never a light field module's.
bool follows_motion(const SceneGpu& scene, const FrameSettings& settings, bool modules);

// Compiles the G-buffer variants the scene's materials need in `targets` (configured for the scene:
// their settings, module kind and motion target; Programs::prepare_gbuffer), and the forward variants
// of its blended ones into a target that encodes sRGB itself or not, so the frames that draw it
// compile nothing.
bool prepare_material_programs(Programs& programs, const SceneGpu& scene, const ViewTargets& targets, bool srgb_target,
                               std::string& error);

void depth_prepass(const PassContext& context);
void gbuffer_pass(const PassContext& context, bool after_prepass);
// The AO passes (depth chain, SSAO, temporal accumulation, blur). Returns false when the last
// frame's AO was kept instead.
bool ao_passes(const PassContext& context);
// Upsampling (when AO is at half resolution), shading and sRGB encoding, into `target`, then the
// scene's blended materials over it (the blend pass; not on light field modules, nor under a debug
// output). `fade` multiplies the image (transitions between playlist items).
void present_pass(const PassContext& context, const PresentTarget& target, float fade);

// The passes before present_pass in order for one view, choosing the prepass as the settings say.
void draw_view(const PassContext& context);
// draw_view, then present_pass.
void render_view(const PassContext& context, const PresentTarget& target, float fade);

}  // namespace render
