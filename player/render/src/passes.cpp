#include "render/passes.h"

#include "gl_util.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cstdio>

namespace render {

using detail::bind_texture;
using detail::groups;

std::string_view pass_name(int pass) {
  switch (pass) {
    case kDepthPrepass: return "depth prepass";
    case kGBuffer: return "g-buffer";
    case kDepthChain: return "depth chain";
    case kSsao: return "ssao";
    case kTemporal: return "temporal";
    case kBlurH: return "blur horizontal";
    case kBlurV: return "blur vertical";
    case kPresent: return "present";
    default: return "?";
  }
}

void Frame::finish_pass(int pass) const {
  if (gl_error != nullptr && targets.settings().check_errors) {
    const GLenum status = gl::api.GetError();
    if (status != GL_NO_ERROR && gl_error->empty()) {
      char text[96];
      std::snprintf(text, sizeof text, "%s: GL error 0x%04x", pass_name(pass).data(), status);
      *gl_error = text;  // only the first error is kept; its capacity suffices after the first frame
    }
  }
  if (timer != nullptr) timer->mark(pass);
}

namespace {

shared_layout::ModuleParams module_params(const ModuleView& view) {
  const lightfield::Module& m = view.module;
  shared_layout::ModuleParams params{};
  params.world_to_physical = glm::mat4(view.roi.world_to_physical());
  params.physical_to_world = glm::mat4(view.roi.physical_to_world());
  params.module = glm::vec4(m.x, m.z, m.observer_distance, m.observer_height);
  params.screen = glm::vec4(m.footprint0, m.footprint1, m.screen_height, view.roi.scale);
  params.depth = glm::vec4(m.z_front, m.z_back, 1.0 / (m.observer_distance - m.z_back), view.seed_cell);
  params.size = glm::ivec4(m.width, m.height, view.pixel_turns ? 1 : 0, 0);
  return params;
}

void draw_scene(const Frame& frame, bool depth_only) {
  const Programs& programs = frame.programs;
  const SceneGpu& scene = frame.scene;
  const bool untextured_variant = frame.targets.settings().untextured_variant;
  const bool modules = frame.view.module.has_value();
  const RasterProgram& depth_program = modules ? programs.module_depth_only : programs.depth_only;
  const RasterProgram& textured_program = modules ? programs.module_gbuffer_textured : programs.gbuffer_textured;
  const RasterProgram& plain_program = modules ? programs.module_gbuffer_plain : programs.gbuffer_plain;
  if (modules) gl::api.BindBufferBase(GL_UNIFORM_BUFFER, BINDING_MODULE_PARAMS, frame.targets.module_ubo.id());
  const glm::mat4 projection(frame.view.projection);
  const RasterProgram* bound = nullptr;
  for (const SceneGpu::Draw& draw : scene.draws()) {
    const scene::Material& material = scene.materials()[static_cast<size_t>(draw.material)];
    const bool textured = material.base_color_texture >= 0;
    const bool fetches = textured || !untextured_variant;
    const RasterProgram* program = depth_only ? &depth_program : fetches ? &textured_program : &plain_program;
    if (program != bound) {
      gl::api.UseProgram(program->program.id());
      gl::api.UniformMatrix4fv(program->projection, 1, GL_FALSE, glm::value_ptr(projection));
      if (program->texture >= 0) gl::api.Uniform1i(program->texture, 0);
      bound = program;
    }
    // Composed in double, then rounded: positions reach the GPU relative to the camera.
    const glm::dmat4 model_view_d = frame.view.view * draw.world;
    const glm::mat4 model_view(model_view_d);
    gl::api.UniformMatrix4fv(program->model_view, 1, GL_FALSE, glm::value_ptr(model_view));
    if (!depth_only) {
      const glm::mat3 normal_matrix(glm::transpose(glm::inverse(glm::dmat3(model_view_d))));
      gl::api.UniformMatrix3fv(program->normal_matrix, 1, GL_FALSE, glm::value_ptr(normal_matrix));
      gl::api.Uniform4fv(program->base_color, 1, glm::value_ptr(material.base_color));
      if (fetches) {
        gl::api.ActiveTexture(GL_TEXTURE0);
        gl::api.BindTexture(GL_TEXTURE_2D, textured ? scene.textures()[static_cast<size_t>(material.base_color_texture)].id()
                                                    : programs.white.id());
      }
    }
    if (material.double_sided) gl::api.Disable(GL_CULL_FACE);
    else gl::api.Enable(GL_CULL_FACE);
    const SceneGpu::Mesh& mesh = scene.meshes()[static_cast<size_t>(draw.mesh)];
    gl::api.BindVertexArray(mesh.vao.id());
    gl::api.DrawElements(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr);
  }
  gl::api.BindVertexArray(0);
}

void begin_raster(const Frame& frame) {
  const FrameSettings& settings = frame.targets.settings();
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, frame.targets.gbuffer_fbo.id());
  gl::api.Viewport(0, 0, settings.width, settings.height);
  gl::api.Enable(GL_DEPTH_TEST);
  gl::api.CullFace(GL_BACK);
  gl::api.FrontFace(GL_CCW);
  const float zero[4] = {0, 0, 0, 0};
  const float one = 1.0f;
  gl::api.ClearBufferfv(GL_COLOR, 0, zero);
  gl::api.ClearBufferfv(GL_COLOR, 1, zero);
  gl::api.ClearBufferfv(GL_COLOR, 2, zero);  // linear depth 0 marks background
  if (frame.targets.modules()) gl::api.ClearBufferfv(GL_COLOR, 3, zero);
  gl::api.DepthMask(GL_TRUE);
  gl::api.ClearBufferfv(GL_DEPTH, 0, &one);
}

float inverse_far(const View& view) { return static_cast<float>(1.0 / view.far); }

// How far a history texel's depth may differ from the reprojected point's, relative to that depth,
// and how far its normal may turn, before it counts as another surface (a disocclusion). The depth
// tolerance covers a slanted face's change across the bilinear footprint; the normal test catches
// what depth cannot tell apart, such as a crease.
constexpr float kHistoryDepthTolerance = 0.03f;
constexpr float kHistoryNormalCosine = 0.9f;

// Blends this frame's AO into the reprojected average of the previous ones (temporal.comp).
void accumulate(const Frame& frame, bool moved) {
  ViewTargets& targets = frame.targets;
  const FrameSettings& settings = targets.settings();
  const View& view = frame.view;
  const glm::dmat4 view_to_world = glm::inverse(view.view);
  shared_layout::TemporalParams& params = targets.temporal_params;
  params.current_to_previous = glm::mat4(targets.ao_view * view_to_world);
  params.previous_projection = glm::mat4(targets.ao_projection);
  params.view_to_world = glm::mat4(view_to_world);
  params.unproject = targets.ssao_params.unproject;
  params.depth = glm::vec4(static_cast<float>(view.far), static_cast<float>(targets.ao_far), kHistoryDepthTolerance,
                           kHistoryNormalCosine);
  params.config = glm::ivec4(targets.have_ao ? 1 : 0, settings.history, targets.ssao_params.config.y, moved ? 1 : 0);
  params.size = glm::ivec4(targets.ao_width(), targets.ao_height(), settings.width, settings.height);
  detail::update_uniform_buffer(targets.temporal_ubo, &params, sizeof params);

  const int previous = targets.history_current, next = 1 - previous;
  gl::api.UseProgram(frame.programs.temporal.id());
  gl::api.BindBufferBase(GL_UNIFORM_BUFFER, BINDING_TEMPORAL_PARAMS, targets.temporal_ubo.id());
  bind_texture(0, targets.ao_raw);
  bind_texture(1, targets.normal);
  bind_texture(2, targets.history[previous]);
  bind_texture(3, targets.history_normal[previous]);
  gl::api.BindImageTexture(0, targets.history[next].id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  gl::api.BindImageTexture(1, targets.history_normal[next].id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8_SNORM);
  gl::api.DispatchCompute(groups(targets.ao_width(), SSAO_GROUP_SIZE), groups(targets.ao_height(), SSAO_GROUP_SIZE), 1);
  gl::api.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  targets.history_current = next;
  frame.finish_pass(kTemporal);
}

}  // namespace

void depth_prepass(const Frame& frame) {
  begin_raster(frame);
  gl::api.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  gl::api.DepthFunc(GL_LESS);
  draw_scene(frame, true);
  gl::api.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  frame.finish_pass(kDepthPrepass);
}

void gbuffer_pass(const Frame& frame, bool after_prepass) {
  if (after_prepass) {
    gl::api.DepthFunc(GL_LEQUAL);
    gl::api.DepthMask(GL_FALSE);
  } else {
    begin_raster(frame);
    gl::api.DepthFunc(GL_LESS);
  }
  draw_scene(frame, false);
  gl::api.DepthMask(GL_TRUE);
  gl::api.Disable(GL_DEPTH_TEST);
  gl::api.Disable(GL_CULL_FACE);
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, 0);
  // GL orders a draw into a texture before a later dispatch that samples it, but Mesa 22.3's
  // llvmpipe starts the dispatch while its rasteriser threads may still be drawing tiles of the
  // G-buffer: SSAO then read cleared tiles as background, seen once frames carried history (two
  // identical runs of 16 frames differed). Any glMemoryBarrier makes llvmpipe wait; elsewhere it
  // costs no more than the wait the dispatch needs anyway.
  gl::api.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
  frame.finish_pass(kGBuffer);
}

bool ao_passes(const Frame& frame) {
  ViewTargets& targets = frame.targets;
  const FrameSettings& settings = targets.settings();
  const View& view = frame.view;
  // A still view over a static scene sees the same AO: keep it rather than compute it again, once
  // the temporal average has all its frames. Light field modules share one set of targets, so each
  // module's AO is computed anew.
  const bool temporal = targets.temporal();
  const bool still = targets.have_ao && view.view == targets.ao_view && view.projection == targets.ao_projection;
  targets.reused_ao = settings.reuse_static_ao && !view.module && still && (!temporal || targets.still_frames >= settings.history);
  if (targets.reused_ao) return false;
  const int w = settings.width, h = settings.height;
  const int ao_w = targets.ao_width(), ao_h = targets.ao_height();
  shared_layout::SsaoParams& params = targets.ssao_params;

  ssao::FrameView frame_view;
  frame_view.projection = glm::mat4(view.projection);
  const double centre_distance = glm::length(view.eye - frame.scene.centre());
  frame_view.centre_depth = static_cast<float>(std::max(centre_distance, view.near));
  frame_view.nearest_depth = static_cast<float>(std::max(centre_distance - frame.scene.radius(), view.near));
  frame_view.scene_radius = static_cast<float>(frame.scene.radius());
  ssao::update_for_frame(params, settings.ao_settings, frame_view);
  if (temporal) ssao::advance_frame(params, targets.ao_frame);
  if (view.module) {
    // Algorithm 2 maps every sample itself and reads the full-resolution depth: no depth chain, and
    // no radius is skipped by a screen-space size that has no meaning here.
    params.radius_range.x = 0;
    params.radius_range.y = params.counts.y;
    params.lods_0_3 = glm::ivec4(0);
    params.config.x = 0;
    params.radius_4_bias.w = 0.0f;
  }

  // Levels are only built when some radius in use reads one.
  int deepest = 0;
  for (int k = params.radius_range.x; k < params.radius_range.y; ++k)
    deepest = std::max(deepest, k < 4 ? params.lods_0_3[k] : params.config.x);
  if (deepest > 0) {
    gl::api.UseProgram(frame.programs.depth_chain.id());
    bind_texture(0, targets.linear_depth);
    for (int level = 1; level <= deepest; ++level) {
      gl::api.Uniform1i(frame.programs.depth_chain_source_level, level - 1);
      gl::api.BindImageTexture(0, targets.linear_depth.id(), level, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
      gl::api.DispatchCompute(groups(std::max(w >> level, 1), SSAO_GROUP_SIZE), groups(std::max(h >> level, 1), SSAO_GROUP_SIZE), 1);
      gl::api.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    frame.finish_pass(kDepthChain);
  }

  detail::update_uniform_buffer(targets.ssao_ubo, &params, sizeof params);
  gl::api.UseProgram(targets.ssao_program->id());
  gl::api.BindBufferBase(GL_UNIFORM_BUFFER, BINDING_SSAO_PARAMS, targets.ssao_ubo.id());
  gl::api.Uniform1f(targets.ssao_inverse_far, inverse_far(view));
  bind_texture(0, targets.linear_depth);
  bind_texture(1, targets.normal);
  if (view.module) {
    bind_texture(2, targets.positions);
    gl::api.BindBufferBase(GL_UNIFORM_BUFFER, BINDING_MODULE_PARAMS, targets.module_ubo.id());
  }
  gl::api.BindImageTexture(0, targets.ao_raw.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  gl::api.DispatchCompute(groups(ao_w, SSAO_GROUP_SIZE), groups(ao_h, SSAO_GROUP_SIZE), 1);
  gl::api.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  frame.finish_pass(kSsao);

  if (temporal) accumulate(frame, !still);

  if (settings.blur.mode != ssao::Blur::off) {
    const gl::Program& blur = settings.blur.mode == ssao::Blur::denoise     ? frame.programs.blur_denoise
                              : settings.blur.mode == ssao::Blur::bilateral ? frame.programs.blur_bilateral
                                                                            : frame.programs.blur_gaussian;
    gl::api.UseProgram(blur.id());
    bind_texture(1, targets.normal);  // read by denoise only
    const gl::Texture* sources[2] = {&targets.ao_unblurred(), &targets.ao_temp};
    const gl::Texture* destinations[2] = {&targets.ao_temp, &targets.ao_blurred};
    for (int direction = 0; direction < 2; ++direction) {
      gl::api.BindBufferBase(GL_UNIFORM_BUFFER, BINDING_BLUR_PARAMS, targets.blur_ubo[direction].id());
      bind_texture(0, *sources[direction]);
      gl::api.BindImageTexture(0, destinations[direction]->id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
      // A work group per run of pixels along the blur direction: x counts runs, y counts lines.
      if (direction == 0) gl::api.DispatchCompute(groups(ao_w, BLUR_GROUP_SIZE), static_cast<GLuint>(ao_h), 1);
      else gl::api.DispatchCompute(groups(ao_h, BLUR_GROUP_SIZE), static_cast<GLuint>(ao_w), 1);
      gl::api.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
      frame.finish_pass(direction == 0 ? kBlurH : kBlurV);
    }
  }
  targets.still_frames = still ? std::min(targets.still_frames + 1, settings.history) : 1;
  targets.ao_view = view.view;
  targets.ao_projection = view.projection;
  targets.ao_far = view.far;
  targets.have_ao = true;
  ++targets.ao_frame;
  return true;
}

void present_pass(const Frame& frame, const PresentTarget& target, float fade) {
  ViewTargets& targets = frame.targets;
  const FrameSettings& settings = targets.settings();
  const View& view = frame.view;
  shared_layout::CompositeParams composite{};
  composite.light_direction = glm::vec4(glm::normalize(glm::vec3(-0.4f, 0.6f, 0.7f)), 0.35f);
  composite.background = glm::vec4(settings.background, 1.0f);
  composite.depth_range = glm::vec4(static_cast<float>(view.near), static_cast<float>(view.far), inverse_far(view), fade);
  composite.config = glm::ivec4(static_cast<int>(settings.output), settings.ao ? 1 : 0, settings.width, settings.height);
  composite.ao_config = glm::ivec4(targets.ao_width(), targets.ao_height(), settings.ao_settings.half_resolution ? 1 : 0, 0);
  composite.viewport = glm::ivec4(target.x, target.y, 0, 0);
  composite.shading = glm::vec4(settings.ao_strength, targets.upsample_plane_tolerance(), 0.0f, 0.0f);
  composite.unproject = targets.ssao_params.unproject;
  detail::update_uniform_buffer(targets.composite_ubo, &composite, sizeof composite);
  targets.last_inverse_far = composite.depth_range.z;

  gl::api.BindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
  gl::api.Viewport(target.x, target.y, settings.width, settings.height);
  gl::api.Disable(GL_DEPTH_TEST);
  gl::api.Disable(GL_CULL_FACE);
  gl::api.UseProgram(targets.present_program->id());  // chosen for target.srgb at configure
  gl::api.BindBufferBase(GL_UNIFORM_BUFFER, BINDING_COMPOSITE_PARAMS, targets.composite_ubo.id());
  bind_texture(0, targets.albedo);
  bind_texture(1, targets.normal);
  bind_texture(2, targets.linear_depth);
  bind_texture(3, targets.ao_result());
  gl::api.BindVertexArray(frame.programs.empty_vertex_array.id());
  gl::api.DrawArrays(GL_TRIANGLES, 0, 3);
  gl::api.BindVertexArray(0);
  // The next frame's compute passes store into the AO images this draw reads. A draw may still be
  // running (llvmpipe bins and rasterises it later) when a dispatch starts, and only this barrier
  // orders image stores after the texture fetches issued before it: without it, frames after the
  // first came out different from run to run.
  gl::api.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  frame.finish_pass(kPresent);
}

void render_view(const Frame& frame, const PresentTarget& target, float fade) {
  ViewTargets& targets = frame.targets;
  const FrameSettings& settings = targets.settings();
  if (frame.view.module) {
    const shared_layout::ModuleParams params = module_params(*frame.view.module);
    detail::update_uniform_buffer(targets.module_ubo, &params, sizeof params);
  }
  switch (settings.prepass) {
    case Prepass::on: targets.prepass_now = true; break;
    case Prepass::off: targets.prepass_now = false; break;
    case Prepass::automatic:  // first frame with, second without, then the faster of the two
      targets.prepass_now = targets.raster_with < 0.0      ? true
                            : targets.raster_without < 0.0 ? false
                                                           : targets.raster_with <= targets.raster_without;
      break;
  }
  if (targets.prepass_now) depth_prepass(frame);
  gbuffer_pass(frame, targets.prepass_now);
  if (settings.ao) ao_passes(frame);
  else targets.reused_ao = false;
  present_pass(frame, target, fade);
}

}  // namespace render
