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
// LightFieldOutput is the part `play` uses with its own programs, scenes and targets;
// LightFieldRenderer puts one together with them for `render`, tests and benchmarks.
#include "gl/caps.h"
#include "lightfield/display_file.h"
#include "render/edge_subdivision.h"
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

class LightFieldOutput {
 public:
  // Fixes the views, allocates the outputs and configures `targets` for the display (`settings`' size
  // is replaced by the module's or view's). Errors name the setting or the display.
  bool configure(Programs& programs, const gl::Caps& caps, const lightfield::Display& display, const FrameSettings& settings,
                 const scene::Bounds& bounds, double scene_radius, ViewTargets& targets, std::string& error);
  // Quilts: the central camera the views are spread around (every frame, for a moving camera).
  // Modules: nothing; their geometry is the display's. Does not allocate.
  void set_camera(const scene::Camera& camera);
  // Renders every view and encodes the output. `probe`: instead of the scene, view k is the flat colour
  // (k, k, k) / 255, so the interleave can be checked subpixel by subpixel. Neither allocates nor throws.
  void render(Programs& programs, const SceneGpu& scene, ViewTargets& targets, float fade, bool probe,
              const AfterView& after_view, std::string* gl_error);
  // What the display is fed, scaled to fit `width` x `height` of `target` (letterboxed): the native
  // panel image of a quilt, the montage of modules.
  void present(const Programs& programs, const PresentTarget& target, int width, int height) const;

  int views() const { return static_cast<int>(views_.size()); }
  int rendered_views() const;
  bool skipped(int view) const { return skipped_[static_cast<size_t>(view)]; }
  const View& view(int k) const { return views_[static_cast<size_t>(k)]; }
  glm::ivec2 view_size() const { return view_size_; }
  glm::ivec2 output_size() const { return output_size_; }  // montage or quilt
  glm::ivec2 native_size() const;                          // quilts: the panel; modules: 0x0
  bool quilt() const { return display_.type == lightfield::DisplayType::quilt; }
  const lightfield::Display& display() const { return display_; }
  // The lower-left pixel of view k's tile in the output image (GL's rows, bottom up).
  glm::ivec2 tile_origin(int k) const;
  // Modules turn their samples per world cell, the same in every module; `true` turns them by pixel
  // tile as 2D views do (only to measure the difference).
  void set_pixel_turns(bool pixel_turns);

  // RGBA8, row 0 at the top (they wait for the GPU: not in the frame loop).
  std::vector<uint8_t> read_output() const;
  std::vector<uint8_t> read_view(int k) const;
  std::vector<uint8_t> read_native() const;

 private:
  lightfield::Display display_;
  glm::vec3 background_{0.0f};
  glm::ivec2 view_size_{0}, output_size_{0}, grid_{1};
  double near_ = 0.1, far_ = 100.0;
  std::vector<View> views_;
  std::vector<bool> skipped_;
  gl::Texture output_texture_, native_texture_;
  gl::Framebuffer output_fbo_, native_fbo_;
  const gl::Program* interleave_ = nullptr;
  GLint interleave_constants_ = -1, interleave_panel_ = -1, interleave_layout_ = -1;
};

// The scene and the views for one display: what `render --display`, the tests and lfbench use.
class LightFieldRenderer {
 public:
  bool init(const gl::Caps& caps, std::string& error);
  // Keeps the scene; configure() uploads it, for modules with its long edges split first.
  bool upload(const scene::Scene& scene, std::string& error);
  // `camera`: the central camera of a quilt (unused for modules). For modules, edges that the
  // per-vertex transform would draw more than kMaxEdgeErrorPx from where the module shows them are
  // split (edge_subdivision.h) before the upload.
  bool configure(const lightfield::Display& display, const FrameSettings& settings, const scene::Camera& camera,
                 std::string& error);
  void render(bool probe = false, const AfterView& after_view = {});

  static constexpr double kMaxEdgeErrorPx = 0.5;
  const SubdivisionReport& subdivision() const { return subdivision_; }
  LightFieldOutput& output() { return output_; }
  const LightFieldOutput& output() const { return output_; }

  // Shorthands for output().
  int views() const { return output_.views(); }
  int rendered_views() const { return output_.rendered_views(); }
  bool skipped(int view) const { return output_.skipped(view); }
  const View& view(int k) const { return output_.view(k); }
  glm::ivec2 view_size() const { return output_.view_size(); }
  glm::ivec2 output_size() const { return output_.output_size(); }
  glm::ivec2 native_size() const { return output_.native_size(); }
  bool quilt() const { return output_.quilt(); }
  void set_pixel_turns(bool pixel_turns) { output_.set_pixel_turns(pixel_turns); }
  std::vector<uint8_t> read_output() const { return output_.read_output(); }
  std::vector<uint8_t> read_view(int k) const { return output_.read_view(k); }
  std::vector<uint8_t> read_native() const { return output_.read_native(); }

  const std::string& gl_error() const { return gl_error_; }
  const ViewTargets& targets() const { return targets_; }
  const Programs& programs() const { return programs_; }

 private:
  gl::Caps caps_;
  Programs programs_;
  std::shared_ptr<const scene::Scene> source_;
  SubdivisionReport subdivision_;
  bool uploaded_ = false;
  lightfield::Display uploaded_for_;  // the display whose geometry the uploaded scene was split for
  SceneGpu scene_;
  ViewTargets targets_;
  LightFieldOutput output_;
  std::string gl_error_;
};

// For modules: the scene with its long edges split for `display` (edge_subdivision.h), as the
// renderer uploads it; `report` says what was done. Quilts: the scene as it is.
scene::Scene prepare_for_display(const scene::Scene& scene, const lightfield::Display& display, SubdivisionReport& report);

}  // namespace render
