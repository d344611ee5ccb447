#pragma once
// Light field output: every optical module (or quilt view) of a display rendered through the one
// pipeline of passes.h, then encoded: a montage of the modules' images, or the quilt and the
// lenticular interleave of the panel's native image.
//
// Shared between views: the programs, the scene's GPU data and its draw list, the sample tables and
// one set of per-view targets (the G-buffer and AO are transient, so N views cost N times the passes,
// not N times the memory). Per view: the transform (the module's world-to-image uniform block, or the
// quilt view's matrices), the G-buffer, SSAO, blur and composite into the view's tile. Modules whose
// image the scene's bounds cannot reach are not rendered (their tile shows the background).
//
// LightFieldOutput is the render::Output (output.h) `play` uses with its own programs and scenes;
// LightFieldRenderer puts one together with them for `render`, tests and benchmarks.
#include "gl/caps.h"
#include "gl/session.h"
#include "lightfield/display_file.h"
#include "render/edge_subdivision.h"
#include "render/output.h"
#include "render/passes.h"
#include "render/programs.h"
#include "render/scene_gpu.h"
#include "render/settings.h"
#include "render/view.h"
#include "render/view_targets.h"
#include "scene/camera.h"
#include "scene/scene.h"

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace render {

// Called after each rendered view while the targets still hold it (dumps, tests).
using AfterView = std::function<void(int view, const View&, const ViewTargets&)>;

class LightFieldOutput final : public Output {
 public:
  // `programs` and `caps` outlive the output.
  LightFieldOutput(Programs& programs, const gl::Caps& caps) : programs_(programs), caps_(caps) {}

  // The display the next configure() is for.
  void show_on(const lightfield::Display& display) { display_ = display; }
  // Fixes the views and allocates the outputs for the display of show_on(); the settings' size is
  // replaced by the module's or view's. Optical modules run Algorithm 2, which the horizon
  // estimator has no form of: they fall back to hemisphere, said in adjustment(). Errors name the
  // setting or the display.
  bool configure(const FrameSettings& settings, const SceneGpu& scene, bool srgb_target, std::string& error) override;
  glm::ivec2 view_size() const override { return view_size_; }
  // Quilts: the central camera the views are spread around. Modules: nothing; their geometry is the
  // display's. Does not allocate.
  void aim(const scene::Camera& camera) override;
  // Renders every view and encodes the output (the quilt's interleave). Views are not timed by pass:
  // `frame.timer` is not used. Neither allocates nor throws.
  void render(const OutputFrame& frame) override;
  // What the display is fed, scaled to fit `width` x `height` of `target` (letterboxed): the native
  // panel image of a quilt, the montage of modules.
  void present(const OutputFrame& frame, const PresentTarget& target, int width, int height) override;

  // For tests and dumps: `probe` draws view k as the flat colour (k, k, k) / 255 instead of the scene,
  // so the interleave can be checked subpixel by subpixel; `after_view` is called after each view.
  void set_probe(bool probe) { probe_ = probe; }
  void set_after_view(AfterView after_view) { after_view_ = std::move(after_view); }
  // Modules turn their samples per world cell, the same in every module; `true` turns them by pixel
  // tile as 2D views do (only to measure the difference).
  void set_pixel_turns(bool pixel_turns);

  int views() const { return static_cast<int>(views_.size()); }
  int rendered_views() const;
  bool skipped(int view) const { return skipped_[static_cast<size_t>(view)]; }
  const View& view(int k) const { return views_[static_cast<size_t>(k)]; }
  glm::ivec2 output_size() const { return output_size_; }  // montage or quilt
  glm::ivec2 native_size() const;                          // quilts: the panel; modules: 0x0
  bool quilt() const { return display_.type == lightfield::DisplayType::quilt; }
  const lightfield::Display& display() const { return display_; }
  const ViewTargets& targets() const { return targets_; }
  // The lower-left pixel of view k's tile in the output image (GL's rows, bottom up).
  glm::ivec2 tile_origin(int k) const;

  // RGBA8, row 0 at the top (they wait for the GPU: not in the frame loop).
  std::vector<uint8_t> read_output() const;
  std::vector<uint8_t> read_view(int k) const;
  std::vector<uint8_t> read_native() const;

 private:
  Programs& programs_;
  const gl::Caps& caps_;
  // One set for every view: the G-buffer and AO are transient, so N views cost N times the passes,
  // not N times the memory.
  ViewTargets targets_;
  lightfield::Display display_;
  glm::vec3 background_{0.0f};
  glm::ivec2 view_size_{0}, output_size_{0}, grid_{1};
  std::vector<View> views_;
  std::vector<bool> skipped_;
  gl::Texture output_texture_, native_texture_;
  gl::Framebuffer output_fbo_, native_fbo_;
  bool probe_ = false;
  AfterView after_view_;
};

// The scene and the output for one display: what `render --display`, the tests and lfbench use.
class LightFieldRenderer {
 public:
  // Builds the programs in `session`, which outlives the renderer.
  bool init(gl::Session& session, std::string& error);
  // Keeps the scene; configure() uploads it, for modules with its long edges split first.
  bool upload(const scene::Scene& scene, std::string& error);
  // `camera`: the central camera of a quilt (unused for modules). For modules, edges that the
  // per-vertex transform would draw more than kMaxEdgeErrorPx from where the module shows them are
  // split (edge_subdivision.h) before the upload.
  bool configure(const lightfield::Display& display, const FrameSettings& settings, const scene::Camera& camera,
                 std::string& error);
  void render();
  // What the display is fed, letterboxed into `width` x `height` of `target`.
  void present(const PresentTarget& target, int width, int height) {
    output_.present(OutputFrame{scene_, 1.0f, nullptr, &gl_error_}, target, width, height);
  }

  static constexpr double kMaxEdgeErrorPx = 0.5;
  const SubdivisionReport& subdivision() const { return subdivision_; }
  LightFieldOutput& output() { return output_; }
  const LightFieldOutput& output() const { return output_; }
  const std::string& gl_error() const { return gl_error_; }
  const Programs& programs() const { return programs_; }

 private:
  gl::Caps caps_;
  Programs programs_;
  std::shared_ptr<const scene::Scene> source_;
  SubdivisionReport subdivision_;
  bool uploaded_ = false;
  lightfield::Display uploaded_for_;  // the display whose geometry the uploaded scene was split for
  SceneGpu scene_;
  LightFieldOutput output_{programs_, caps_};
  std::string gl_error_;
};

// For modules: the scene with its long edges split for `display` (edge_subdivision.h), as the
// renderer uploads it; `report` says what was done. Quilts: the scene as it is.
scene::Scene prepare_for_display(const scene::Scene& scene, const lightfield::Display& display, SubdivisionReport& report);

}  // namespace render
