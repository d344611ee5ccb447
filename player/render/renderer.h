#pragma once
// The paper's six-pass deferred frame on GLES 3.1: depth prepass, G-buffer, SSAO (compute),
// horizontal and vertical blur (compute), composite (compute). One instance per context.
#include "gl/caps.h"
#include "gl/objects.h"
#include "gl/pass_timer.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "ssao/params.h"

#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace render {

enum class View { color, ao, normal, depth };

// The depth prepass pays only where overdraw is high enough that shading fragments twice costs more
// than drawing the geometry twice; `automatic` measures both on the first two frames and keeps the faster.
enum class Prepass { off, on, automatic };
std::string_view name(Prepass prepass);
std::string_view name(View view);

struct FrameSettings {
  int width = 1024, height = 768;
  bool ao = true;
  ssao::AoSettings ao_settings;
  ssao::BlurSettings blur;
  float radius = 0.0f;        // base AO radius in world units; 0: a tenth of the scene's bounding radius
  View view = View::color;
  Prepass prepass = Prepass::automatic;
  bool reuse_static_ao = true;  // while camera and scene stand still, keep the last frame's AO
  // Untextured materials draw with the G-buffer variant that fetches no texture. Off only to measure
  // what that saves (aobench's untextured=fetch): they then sample a 1x1 white texture.
  bool untextured_variant = true;
  bool check_errors = false;    // glGetError after each pass (tests, debug runs)
};

enum Pass { kDepthPrepass, kGBuffer, kDepthChain, kSsao, kBlurH, kBlurV, kUpsample, kComposite, kPassCount };
std::string_view pass_name(int pass);

struct PassTimes {
  std::array<double, kPassCount> ms{};  // negative: the pass did not run
  bool gpu_timed = false;               // false: CPU time around glFinish
};

class Renderer {
 public:
  Renderer() = default;
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Compiles every program variant. Returns false and says why.
  bool init(const gl::Caps& caps, std::string& error);
  // Uploads the scene's meshes and textures.
  bool upload(const scene::Scene& scene, std::string& error);
  // Allocates the render targets and fixes the per-frame constants for these settings.
  bool configure(const FrameSettings& settings, std::string& error);

  // One frame. Neither allocates nor throws; a GL error is recorded, not raised.
  void render(const scene::Camera& camera);

  PassTimes collect_times();
  // The first GL error seen since configure(), as "pass: GL error 0x...", or empty.
  const std::string& gl_error() const { return gl_error_; }

  // Read-backs for output and tests; rows bottom-up (GL order) except read_color.
  std::vector<uint8_t> read_color() const;  // RGBA8, row 0 at the top
  std::vector<float> read_linear_depth() const;
  std::vector<glm::vec3> read_view_normals() const;
  std::vector<glm::vec2> read_ao_raw() const;      // at the AO resolution (half with half_resolution)
  std::vector<glm::vec2> read_ao_blurred() const;  // ditto; equal to read_ao_raw() with blur off
  std::vector<glm::vec2> read_ao_final() const;    // full resolution: what the composite used

  const shared_layout::SsaoParams& ssao_params() const { return ssao_params_; }
  const shared_layout::BlurParams& blur_params(int direction) const { return blur_params_[direction]; }
  const shared_layout::UpsampleParams& upsample_params() const { return upsample_params_; }
  bool reused_ao() const { return reused_ao_; }  // the last frame kept the AO of the one before
  // With Prepass::automatic: whether the prepass is in use, and the raster times (prepass + G-buffer,
  // G-buffer alone) it was chosen by; negative until both were measured.
  bool prepass_in_use() const { return prepass_now_; }
  double raster_ms_with_prepass() const { return raster_with_; }
  double raster_ms_without_prepass() const { return raster_without_; }
  float base_radius() const { return base_radius_; }
  float inverse_far() const { return inverse_far_; }
  const FrameSettings& settings() const { return settings_; }

 private:
  struct GpuMesh {
    gl::VertexArray vao;
    gl::Buffer vertices, indices;
    GLsizei index_count = 0;
  };
  struct Draw {
    int mesh;
    int material;
    glm::dmat4 world;
  };
  struct GBufferProgram {
    gl::Program program;
    GLint model_view = -1, projection = -1, normal_matrix = -1, base_color = -1, texture = -1;
  };

  bool build_gbuffer_program(GBufferProgram& out, const std::string& fragment, const std::string& defines, std::string& error);
  void draw_scene(bool depth_only, const glm::dmat4& view, const glm::mat4& projection);
  void check(int pass);
  std::vector<glm::vec2> read_ao(const gl::Texture& texture, int width, int height) const;
  std::vector<float> read_rgba_float(const gl::Texture& texture, int width, int height) const;

  gl::Caps caps_;
  FrameSettings settings_;
  gl::PassTimer timer_;
  std::string gl_error_;

  GBufferProgram gbuffer_plain_, gbuffer_textured_, depth_only_;
  gl::Program ssao_, depth_chain_, blur_gaussian_, blur_bilateral_, upsample_, composite_;
  GLint ssao_inverse_far_ = -1, depth_chain_source_level_ = -1;
  int depth_levels_ = 1;

  std::vector<GpuMesh> meshes_;
  std::vector<gl::Texture> textures_;
  std::vector<scene::Material> materials_;
  std::vector<Draw> draws_;  // sorted so untextured and textured draws each form one run
  double scene_radius_ = 1.0;
  glm::dvec3 scene_centre_{0.0};

  gl::Texture white_;  // stands in for a missing base colour texture when untextured_variant is off
  gl::Texture albedo_, normal_, linear_depth_, depth_, ao_raw_, ao_temp_, ao_blurred_, ao_full_, output_;
  gl::Framebuffer gbuffer_fbo_, read_fbo_;
  gl::Buffer ssao_ubo_, blur_ubo_[2], upsample_ubo_, composite_ubo_;
  shared_layout::SsaoParams ssao_params_{};
  shared_layout::BlurParams blur_params_[2]{};
  shared_layout::UpsampleParams upsample_params_{};
  float base_radius_ = 0.0f, inverse_far_ = 0.0f;
  glm::dmat4 last_view_{0.0}, last_projection_{0.0};
  bool have_ao_ = false, reused_ao_ = false;
  bool prepass_now_ = true;
  double raster_with_ = -1.0, raster_without_ = -1.0;
};

}  // namespace render
