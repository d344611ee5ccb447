#pragma once
// Where a frame goes: one interface for the two ways a scene is shown. A view output is one camera
// onto a framebuffer; a light field output (render/light_field.h) is every optical module or quilt
// view of a display, then what that display is fed. `play`, `render`, the tests and the benchmarks
// all draw a frame the same way through it:
//
//   output.configure(settings, scene, srgb, error);            // per item, scene or settings change
//   output.aim(camera);                                        // per frame
//   output.render(frame);  output.present(frame, target, w, h);
#include "gl/caps.h"
#include "gl/frame_timer.h"
#include "render/passes.h"
#include "render/programs.h"
#include "render/scene_gpu.h"
#include "render/settings.h"
#include "render/view.h"
#include "render/view_targets.h"
#include "scene/camera.h"

#include <glm/glm.hpp>

#include <string>

namespace render {

// What one frame draws: the scene, the fade of a transition between items, the pass timer (null:
// untimed) and where the frame's first GL error goes (null: not checked).
struct OutputFrame {
  const SceneGpu& scene;
  float fade = 1.0f;
  gl::FrameTimer* timer = nullptr;
  std::string* gl_error = nullptr;
};

class Output {
 public:
  virtual ~Output() = default;
  // Fixes the views and allocates what they render into, for `settings` (a view's size is the
  // settings' own; a light field display has its modules' or views'), `scene` (its bounds and
  // radius; it is uploaded), presented into a framebuffer that encodes sRGB itself (`srgb_target`)
  // or not. What the output had to change in the settings to show them is in adjustment(). False
  // and why, naming the setting or the display's file.
  virtual bool configure(const FrameSettings& settings, const SceneGpu& scene, bool srgb_target, std::string& error) = 0;
  // The size a camera is framed for: the view's, or one quilt view's or module's.
  virtual glm::ivec2 view_size() const = 0;
  // The next frame's camera: the view itself, or the centre a quilt's views spread around (a display
  // of optical modules has its own geometry and keeps it). Does not allocate.
  virtual void aim(const scene::Camera& camera) = 0;
  // Every view's passes up to the shaded image. Neither allocates nor throws.
  virtual void render(const OutputFrame& frame) = 0;
  // What is shown, into `width` x `height` of `target` (a light field output letterboxes its image;
  // a view is presented at its configured size). Neither allocates nor throws.
  virtual void present(const OutputFrame& frame, const PresentTarget& target, int width, int height) = 0;

  // The settings configure() changed, and why, for the log; empty when it took them as they were.
  const std::string& adjustment() const { return adjustment_; }

 protected:
  std::string adjustment_;
};

// One camera onto a framebuffer: the passes of passes.h, the present pass last.
class ViewOutput final : public Output {
 public:
  // `programs` and `caps` outlive the output.
  ViewOutput(Programs& programs, const gl::Caps& caps) : programs_(programs), caps_(caps) {}

  bool configure(const FrameSettings& settings, const SceneGpu& scene, bool srgb_target, std::string& error) override;
  glm::ivec2 view_size() const override { return {targets_.settings().width, targets_.settings().height}; }
  void aim(const scene::Camera& camera) override { view_ = view_of(camera); }
  // A view that is not a camera's (an off-axis window, a test's matrices).
  void aim(const View& view) { view_ = view; }
  void render(const OutputFrame& frame) override;
  void present(const OutputFrame& frame, const PresentTarget& target, int width, int height) override;

  const View& view() const { return view_; }
  ViewTargets& targets() { return targets_; }
  const ViewTargets& targets() const { return targets_; }

 private:
  PassContext context(const OutputFrame& frame) { return {programs_, frame.scene, targets_, view_, frame.timer, frame.gl_error}; }

  Programs& programs_;
  const gl::Caps& caps_;
  ViewTargets targets_;
  View view_;
};

}  // namespace render
