#include "render/view_targets.h"

#include "gl_util.h"
#include "render/passes.h"

#include <vector>

namespace render {

using detail::make_target;
using detail::make_uniform_buffer;

void ViewTargets::reset_history() {
  have_ao = reused_ao = false;
  ao_frame = 0;
  still_frames = 0;
  raster_with = raster_without = -1.0;
}

bool ViewTargets::configure(Programs& programs, const gl::Caps& caps, const FrameSettings& settings, const SceneGpu& scene,
                            bool srgb_target, std::string& error, bool modules) {
  const bool with_motion = follows_motion(scene, settings, modules);
  const double scene_radius = scene.radius();
  if (settings.width < 1 || settings.height < 1 || settings.width > caps.max_texture_size ||
      settings.height > caps.max_texture_size) {
    error = "--size: " + std::to_string(settings.width) + "x" + std::to_string(settings.height) + " is outside 1.." +
            std::to_string(caps.max_texture_size) + " per side";
    return false;
  }
  if (modules && !programs.build_module_programs(error)) return false;
  ssao_program = programs.ssao(settings.ao_settings.estimator, settings.ao_settings.precision, error, modules);
  if (ssao_program == nullptr) return false;
  ssao_inverse_far = programs.ssao_inverse_far(settings.ao_settings.estimator, settings.ao_settings.precision, modules);
  ssao_defines = programs.ssao_defines(settings.ao_settings.estimator, settings.ao_settings.precision, modules);
  const bool tiles = settings.present_tiles && !modules;
  present_program = programs.present(settings.output, srgb_target, scene.light_count() > 0, error,
                                     tiles ? PresentDraw::bounds : PresentDraw::fullscreen);
  if (present_program == nullptr) return false;
  present_background = nullptr;
  present_tile_scale = -1;
  if (tiles) {
    present_background = programs.present(settings.output, srgb_target, false, error, PresentDraw::background);
    if (present_background == nullptr || !programs.build_covered_bounds(error)) return false;
    present_tile_scale = gl::uniform(*present_program, "u_tile_scale");
  }
  if (with_motion && !programs.build_temporal_motion(error)) return false;
  settings_ = settings;
  reset_history();

  const int w = settings.width, h = settings.height;
  base_radius = settings.radius > 0.0f ? settings.radius : static_cast<float>(0.1 * scene_radius);
  ssao_params = ssao::pack_ssao_params(settings.ao_settings, base_radius, w, h);
  for (int direction = 0; direction < 2; ++direction)
    blur_params[direction] =
        ssao::pack_blur_params(settings.blur, direction, ao_width(), ao_height(), settings.ao_settings.half_resolution ? 1 : 0);

  const bool reallocate = w != width_ || h != height_ || settings.ao_settings.half_resolution != half_ || modules != modules_ ||
                          with_motion != motion_ || !gbuffer_fbo;
  if (reallocate) {
    depth_levels = ssao::depth_chain_levels(w, h);
    albedo = make_target(GL_RGBA8, w, h);
    normal = make_target(GL_RGBA16F, w, h);
    linear_depth = make_target(GL_R32F, w, h, depth_levels);
    depth = make_target(GL_DEPTH_COMPONENT32F, w, h);
    ao_raw = make_target(GL_RGBA16F, ao_width(), ao_height());
    ao_temp = make_target(GL_RGBA16F, ao_width(), ao_height());
    ao_blurred = make_target(GL_RGBA16F, ao_width(), ao_height());

    gbuffer_fbo = gl::make_framebuffer();
    gl::api.BindFramebuffer(GL_FRAMEBUFFER, gbuffer_fbo.id());
    gl::api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, albedo.id(), 0);
    gl::api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, normal.id(), 0);
    gl::api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, GL_TEXTURE_2D, linear_depth.id(), 0);
    gl::api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth.id(), 0);
    material = make_target(GL_RG32UI, w, h);
    // Light field modules on a GPU of four draw buffers keep the positions texture and leave the
    // material target out: it stays cleared (material.glsl's default material) and is only read.
    material_attached_ = !(modules && programs.modules_without_material);
    positions = modules ? make_target(GL_RGBA32F, w, h) : gl::Texture{};
    std::vector<GLenum> buffers = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
    if (material_attached_) {
      gl::api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT3, GL_TEXTURE_2D, material.id(), 0);
      buffers.push_back(GL_COLOR_ATTACHMENT3);
    }
    if (modules) {
      const GLenum attachment = material_attached_ ? GL_COLOR_ATTACHMENT4 : GL_COLOR_ATTACHMENT3;
      gl::api.FramebufferTexture2D(GL_FRAMEBUFFER, attachment, GL_TEXTURE_2D, positions.id(), 0);
      buffers.push_back(attachment);
    }
    motion = with_motion ? make_target(GL_RGBA16F, w, h) : gl::Texture{};
    if (with_motion) {
      gl::api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT4, GL_TEXTURE_2D, motion.id(), 0);
      buffers.push_back(GL_COLOR_ATTACHMENT4);
    }
    gl::api.DrawBuffers(static_cast<GLsizei>(buffers.size()), buffers.data());
    const GLenum status = gl::api.CheckFramebufferStatus(GL_FRAMEBUFFER);
    gl::api.BindFramebuffer(GL_FRAMEBUFFER, 0);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      error = "the G-buffer framebuffer is incomplete (status 0x" + std::to_string(status) + ")";
      gbuffer_fbo.reset();
      return false;
    }
    if (!material_attached_) {
      gl::Framebuffer clear = gl::make_framebuffer();
      gl::api.BindFramebuffer(GL_FRAMEBUFFER, clear.id());
      gl::api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, material.id(), 0);
      const GLuint value[4] = {kMaterialClearX, 0, 0, 0};
      gl::api.ClearBufferuiv(GL_COLOR, 0, value);
      gl::api.BindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    // The projection and the radii in use change with the camera; the passes refresh them.
    ssao_ubo = make_uniform_buffer(&ssao_params, sizeof ssao_params);
    for (int direction = 0; direction < 2; ++direction)
      blur_ubo[direction] = make_uniform_buffer(&blur_params[direction], sizeof blur_params[direction]);
    shared_layout::CompositeParams composite{};
    composite_ubo = make_uniform_buffer(&composite, sizeof composite);
    temporal_params = shared_layout::TemporalParams{};
    temporal_ubo = make_uniform_buffer(&temporal_params, sizeof temporal_params);
    shared_layout::ModuleParams module_params{};
    module_ubo = modules ? make_uniform_buffer(&module_params, sizeof module_params) : gl::Buffer{};
    modules_ = modules;
    motion_ = with_motion;
    width_ = w;
    height_ = h;
    half_ = settings.ao_settings.half_resolution;
  } else {
    detail::update_uniform_buffer(ssao_ubo, &ssao_params, sizeof ssao_params);
    for (int direction = 0; direction < 2; ++direction)
      detail::update_uniform_buffer(blur_ubo[direction], &blur_params[direction], sizeof blur_params[direction]);
  }
  if (!tiles) {
    covered_bounds = gl::Buffer{};
    bounds_vertex_array = gl::VertexArray{};
  } else if (reallocate || !covered_bounds) {
    empty_bounds.clear();
    for (int band = 0; band < tile_bands(); ++band) empty_bounds.insert(empty_bounds.end(), {~0u, ~0u, 0u, 0u});
    covered_bounds = gl::make_buffer();
    gl::api.BindBuffer(GL_ARRAY_BUFFER, covered_bounds.id());
    gl::api.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(empty_bounds.size() * sizeof(GLuint)), nullptr, GL_DYNAMIC_COPY);
    bounds_vertex_array = gl::make_vertex_array();
    gl::api.BindVertexArray(bounds_vertex_array.id());
    gl::api.EnableVertexAttribArray(0);
    gl::api.VertexAttribIPointer(0, 4, GL_UNSIGNED_INT, 0, nullptr);
    gl::api.VertexAttribDivisor(0, 1);  // a band's rectangle for each instance's six vertices
    gl::api.BindVertexArray(0);
    gl::api.BindBuffer(GL_ARRAY_BUFFER, 0);
  }
  // The history is allocated only where it is used (light field outputs never accumulate).
  for (int i = 0; i < 2; ++i) {
    if (!settings.temporal) {
      history[i] = gl::Texture{};
      history_normal[i] = gl::Texture{};
    } else if (reallocate || !history[i]) {
      history[i] = make_target(GL_RGBA32F, ao_width(), ao_height());
      history_normal[i] = make_target(GL_RGBA8_SNORM, ao_width(), ao_height());
    }
  }
  const GLenum gl_status = gl::api.GetError();
  if (gl_status != GL_NO_ERROR) {
    error = "allocating render targets raised GL error 0x" + std::to_string(gl_status);
    return false;
  }
  return true;
}

}  // namespace render
