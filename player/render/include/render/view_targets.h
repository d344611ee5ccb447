#pragma once
// What one view renders into and remembers: the G-buffer and AO textures at its size, its uniform
// blocks, its AO history (kept while the view stands still) and its depth-prepass choice.
#include "gl/caps.h"
#include "gl/objects.h"
#include "render/programs.h"
#include "render/scene_gpu.h"
#include "render/settings.h"

#include <cstdint>
#include <string>
#include <vector>

namespace render {

class ViewTargets {
 public:
  // (Re)allocates the textures when the size or AO resolution changed and fixes the per-frame
  // constants for these settings and a scene of `scene_radius`. Returns false and says why.
  // `srgb_target`: the framebuffer the view is presented into encodes sRGB itself.
  // `modules`: the targets of light field modules (a positions texture for Algorithm 2, the
  // module's uniform block, the LIGHTFIELD_MODULES programs).
  // What the scene asks of them: its radius (the AO radius), whether it has lights of its own (the
  // present variant) and whether it moves (a motion target, follows_motion()).
  bool configure(Programs& programs, const gl::Caps& caps, const FrameSettings& settings, const SceneGpu& scene, bool srgb_target,
                 std::string& error, bool modules = false);
  // Forgets the AO history and the prepass measurement (a new scene or a camera cut).
  void reset_history();

  const FrameSettings& settings() const { return settings_; }
  int ao_width() const { return ssao_params.ao_width; }
  int ao_height() const { return ssao_params.ao_height; }
  // Whether this view accumulates AO over frames (LightFieldOutput turns it off: its views share
  // one set of targets, so the previous frame there is another view's).
  bool temporal() const { return settings_.temporal; }
  // The AO before the blur: this frame's, or its average over frames (at the AO resolution).
  const gl::Texture& ao_unblurred() const { return temporal() ? history[history_current] : ao_raw; }
  // The AO texture the present pass reads: blurred when a blur is on, else ao_unblurred().
  const gl::Texture& ao_result() const { return settings_.blur.mode != ssao::Blur::off ? ao_blurred : ao_unblurred(); }

  bool modules() const { return modules_; }
  // upsample.glsl's plane tolerance. Measured on the six shared scenes after 16 frames (player render
  // + aoref, docs/ao.md "AO in motion"): the error's high-frequency noise fell from 0.00247 to 0.00236 and
  // the MAE from 0.0055 to 0.0054 (one frame's: 0.0035 and 0.0076, both a little lower too); 0.001 did
  // no better, 0.004 less well. Light field modules weigh by depth alone: their pixels are not one
  // pinhole's, so unproject does not place them.
  float upsample_plane_tolerance() const { return modules_ ? 0.0f : 0.002f; }

  gl::Texture albedo, normal, linear_depth, depth, ao_raw, ao_temp, ao_blurred;
  gl::Texture material;  // rg32ui, gles_shaders/material.glsl
  // The cleared material texel (material.glsl's MATERIAL_CLEAR_X): rough, dielectric, unoccluded.
  static constexpr GLuint kMaterialClearX = 0x00FF00FFu;
  // Whether the G-buffer pass writes `material` (see Programs::modules_without_material).
  bool material_attached() const { return material_attached_; }
  gl::Texture positions;  // modules only: world position per pixel, a = 1 on objects
  // An animated scene's only (RGBA16F, attachment 4): xyz, each pixel's surface point's previous
  // view position minus its current one, 0 where nothing moved (gbuffer.frag's MOTION).
  gl::Texture motion;
  bool motion_attached() const { return motion_; }
  // Temporal accumulation, ping-ponged: r = averaged AO, g = depth / far, b = frames averaged (rgba32f); and
  // the world normal of each texel, for the next frame's disocclusion test.
  gl::Texture history[2], history_normal[2];
  int history_current = 0;  // the one written last
  gl::Framebuffer gbuffer_fbo;
  gl::Buffer ssao_ubo, blur_ubo[2], composite_ubo, temporal_ubo;
  gl::Buffer module_ubo;  // modules only: shared_layout::ModuleParams of the module being drawn
  shared_layout::SsaoParams ssao_params{};
  shared_layout::BlurParams blur_params[2]{};
  shared_layout::TemporalParams temporal_params{};
  const gl::Program* ssao_program = nullptr;
  std::string_view ssao_defines;  // the #defines ssao_program was compiled with (its variant)
  const gl::Program* present_program = nullptr;
  // The rectangles of the view's bands that hold its surfaces (FrameSettings::present_tiles), as
  // covered_bounds.comp leaves them (four uints each, in tiles) and the present program reads them
  // (an attribute of bounds_vertex_array, per instance), what they are reset to each frame, the
  // background program drawn before them and the tiles' scale uniform. Empty where the present
  // pass covers the whole view.
  gl::Buffer covered_bounds;
  gl::VertexArray bounds_vertex_array;
  std::vector<GLuint> empty_bounds;
  const gl::Program* present_background = nullptr;
  GLint present_tile_scale = -1;
  bool present_tiles() const { return static_cast<bool>(covered_bounds); }
  int tile_columns() const { return (width_ + Programs::kPresentTile - 1) / Programs::kPresentTile; }
  int tile_rows() const { return (height_ + Programs::kPresentTile - 1) / Programs::kPresentTile; }
  int tile_bands() const { return (tile_rows() + Programs::kPresentBandTiles - 1) / Programs::kPresentBandTiles; }
  GLint ssao_inverse_far = -1;
  int depth_levels = 1;
  float base_radius = 0.0f;
  float last_inverse_far = 0.0f;  // 1 / far of the last frame presented (the AO's g channel is depth / far)

  // History: the AO of the last frame stays valid while view and projection do not change.
  glm::dmat4 ao_view{0.0}, ao_projection{0.0};
  double ao_far = 0.0;
  std::uint64_t ao_pose_version = 0;  // the scene's pose the AO was computed for (SceneGpu::pose_version)
  bool have_ao = false, reused_ao = false;
  unsigned ao_frame = 0;  // frames computed since the history began: the sample turn's sequence index
  int still_frames = 0;   // of them, how many in a row with this view (the average's frames, capped)
  // Prepass::automatic: the raster time with and without the prepass, measured on the first frames.
  bool prepass_now = true;
  double raster_with = -1.0, raster_without = -1.0;

 private:
  FrameSettings settings_;
  int width_ = 0, height_ = 0;
  bool half_ = false, modules_ = false, material_attached_ = true, motion_ = false;
};

}  // namespace render
