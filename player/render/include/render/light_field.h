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
#include <string>
#include <vector>

namespace render {

class LightFieldRenderer {
 public:
  bool init(const gl::Caps& caps, std::string& error);
  // Keeps the scene; configure() uploads it, for modules with its long edges split first.
  bool upload(const scene::Scene& scene, std::string& error);
  // `settings`' size is replaced by the module's or view's; `camera` is the central camera of a quilt
  // (unused for modules, whose geometry is the display's). Errors name the setting or the display.
  // For modules, edges that the per-vertex transform would draw more than kMaxEdgeErrorPx from where
  // the module shows them are split (edge_subdivision.h) before the upload.
  bool configure(const lightfield::Display& display, const FrameSettings& settings, const scene::Camera& camera,
                 std::string& error);

  // Called after each rendered view while the targets still hold it (dumps, tests).
  using AfterView = std::function<void(int view, const View&, const ViewTargets&)>;
  // Renders every view and encodes the output. `probe`: instead of the scene, view k is the flat colour
  // (k, k, k) / 255, so the interleave can be checked subpixel by subpixel.
  void render(bool probe = false, const AfterView& after_view = {});
  // Modules turn their samples per world cell, the same in every module; `true` turns them by pixel
  // tile as 2D views do (only to measure the difference).
  void set_pixel_turns(bool pixel_turns);

  static constexpr double kMaxEdgeErrorPx = 0.5;
  const SubdivisionReport& subdivision() const { return subdivision_; }

  int views() const { return static_cast<int>(views_.size()); }
  int rendered_views() const;      // views not skipped in the last render()
  bool skipped(int view) const { return skipped_[static_cast<size_t>(view)]; }
  const View& view(int k) const { return views_[static_cast<size_t>(k)]; }
  glm::ivec2 view_size() const { return {settings_.width, settings_.height}; }
  glm::ivec2 output_size() const { return output_size_; }  // montage or quilt
  glm::ivec2 native_size() const;                          // quilts: the panel; modules: 0x0
  bool quilt() const { return display_.type == lightfield::DisplayType::quilt; }

  // RGBA8, row 0 at the top. read_output: the montage (module 0 top left, in reading order) or the
  // quilt (view 0 bottom left); read_view: one module's or view's image; read_native: the panel image.
  std::vector<uint8_t> read_output() const;
  std::vector<uint8_t> read_view(int k) const;
  std::vector<uint8_t> read_native() const;
  // The lower-left pixel of view k's tile in the output image (GL's rows, bottom up).
  glm::ivec2 tile_origin(int k) const;

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
  scene::Bounds bounds_;
  ViewTargets targets_;
  lightfield::Display display_;
  FrameSettings settings_;
  std::vector<View> views_;
  std::vector<bool> skipped_;
  glm::ivec2 output_size_{0}, grid_{1};
  gl::Texture output_texture_, native_texture_;
  gl::Framebuffer output_fbo_, native_fbo_;
  gl::Program interleave_;
  GLint interleave_constants_ = -1, interleave_panel_ = -1, interleave_layout_ = -1;
  std::string gl_error_;
};

}  // namespace render
