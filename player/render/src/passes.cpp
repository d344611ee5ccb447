#include "render/passes.h"

#include "gl_util.h"
#include "render/uniform_blocks.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cstdio>

namespace render {

using detail::bind_texture;
using detail::groups;

std::string_view pass_name(Pass pass) {
  switch (pass) {
    case Pass::depth_prepass:
      return "depth prepass";
    case Pass::gbuffer:
      return "g-buffer";
    case Pass::depth_chain:
      return "depth chain";
    case Pass::ssao:
      return "ssao";
    case Pass::temporal:
      return "temporal";
    case Pass::blur_h:
      return "blur horizontal";
    case Pass::blur_v:
      return "blur vertical";
    case Pass::present:
      return "present";
    case Pass::blend:
      return "blend";
  }
  return "?";
}

void PassContext::finish_pass(Pass pass) const {
  if (gl_error != nullptr && targets.settings().check_errors) {
    const GLenum status = gl::api.GetError();
    if (status != GL_NO_ERROR && gl_error->empty()) {
      char text[96];
      std::snprintf(text, sizeof text, "%s: GL error 0x%04x", pass_name(pass).data(), status);
      *gl_error = text;  // only the first error is kept; its capacity suffices after the first frame
    }
  }
  if (timer != nullptr) timer->mark(static_cast<int>(pass));
}

namespace {

void bind_material_texture(int unit, const SceneGpu& scene, const scene::TextureSlot& slot) {
  if (!slot.present()) return;
  gl::api.ActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
  gl::api.BindTexture(GL_TEXTURE_2D, scene.textures()[static_cast<size_t>(slot.texture)].id());
}

// Sets what `program` (bound, its projection set) reads of `draw`: the transforms, and unless
// `depth_only` the material's factors and textures; then draws it.
void draw_one(const PassContext& context, const RasterProgram& program, const SceneGpu::Draw& draw, unsigned bits,
              bool depth_only) {
  const SceneGpu& scene = context.scene;
  const scene::Material& material = scene.materials()[static_cast<size_t>(draw.material)];
  const bool masked = (bits & features::alpha_mask) != 0;
  // Composed in double, then rounded: positions reach the GPU relative to the camera.
  const glm::dmat4 model_view_d = context.view.view * draw.world;
  const glm::mat4 model_view(model_view_d);
  gl::api.UniformMatrix4fv(program.model_view, 1, GL_FALSE, glm::value_ptr(model_view));
  // A mirroring transform turns the winding round (glTF: the determinant decides which side is front).
  const bool mirrored = glm::determinant(glm::dmat3(model_view_d)) < 0.0;
  gl::api.FrontFace(mirrored ? GL_CW : GL_CCW);
  if (!depth_only) {
    gl::api.Uniform1f(program.frame_handedness, mirrored ? -1.0f : 1.0f);
    const glm::mat3 normal_matrix(glm::transpose(glm::inverse(glm::dmat3(model_view_d))));
    gl::api.UniformMatrix3fv(program.normal_matrix, 1, GL_FALSE, glm::value_ptr(normal_matrix));
    gl::api.Uniform1f(program.lit, material.unlit ? 0.0f : 1.0f);
    const glm::vec4 factors(material.metallic, material.roughness, material.normal_scale, material.occlusion_strength);
    gl::api.Uniform4fv(program.material, 1, glm::value_ptr(factors));
    gl::api.Uniform3fv(program.emissive, 1, glm::value_ptr(material.emissive));
    bind_material_texture(unit_metallic_roughness, scene, material.metallic_roughness);
    bind_material_texture(unit_normal, scene, material.normal);
    bind_material_texture(unit_occlusion, scene, material.occlusion);
    bind_material_texture(unit_emissive, scene, material.emissive_texture);
  }
  if (!depth_only || masked) {
    gl::api.Uniform4fv(program.base_color, 1, glm::value_ptr(material.base_color));
    if (masked) gl::api.Uniform1f(program.alpha_cutoff, material.alpha_cutoff);
    if (bits & features::base_color_texture) {
      gl::api.ActiveTexture(GL_TEXTURE0 + unit_base_color);
      gl::api.BindTexture(GL_TEXTURE_2D, material.base_color_texture >= 0
                                             ? scene.textures()[static_cast<size_t>(material.base_color_texture)].id()
                                             : context.programs.white.id());
    }
  }
  if (material.double_sided)
    gl::api.Disable(GL_CULL_FACE);
  else
    gl::api.Enable(GL_CULL_FACE);
  if (bits & features::skinned) gl::api.Uniform1i(program.joint_base, draw.joint_base);
  if (bits & features::motion) {
    const glm::mat4 previous_model_view(context.view.view * draw.previous_world);
    gl::api.UniformMatrix4fv(program.previous_model_view, 1, GL_FALSE, glm::value_ptr(previous_model_view));
  }
  const SceneGpu::Mesh& mesh = scene.meshes()[static_cast<size_t>(draw.mesh)];
  gl::api.BindVertexArray(mesh.vao.id());
  gl::api.DrawElements(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr);
}

// Binds `program` with the view's projection unless it is the one bound.
void use_program(const RasterProgram& program, const RasterProgram*& bound, const glm::mat4& projection) {
  if (&program == bound) return;
  gl::api.UseProgram(program.program->id());
  gl::api.UniformMatrix4fv(program.projection, 1, GL_FALSE, glm::value_ptr(projection));
  bound = &program;
}

// The state draw_one leaves, back to what the other passes expect.
void end_draws() {
  gl::api.BindVertexArray(0);
  gl::api.ActiveTexture(GL_TEXTURE0);
  gl::api.FrontFace(GL_CCW);
}

void draw_scene(const PassContext& context, bool depth_only) {
  const Programs& programs = context.programs;
  const SceneGpu& scene = context.scene;
  const bool untextured_variant = context.targets.settings().untextured_variant;
  const bool modules = context.view.module.has_value();
  const unsigned motion = !depth_only && context.targets.motion_attached() ? features::motion : 0;
  const RasterProgram& depth_program = modules ? programs.module_depth_only : programs.depth_only;
  const RasterProgram& masked_depth_program = modules ? programs.module_depth_masked : programs.depth_masked;
  if (modules) gl::api.BindBufferBase(GL_UNIFORM_BUFFER, BINDING_MODULE_PARAMS, context.targets.module_ubo.id());
  bind_texture(unit_joints, scene.joint_matrices());
  const glm::mat4 projection(context.view.projection);
  const RasterProgram* bound = nullptr;
  // A light field module has no forward pass: its blended materials are alpha-tested at their cutoff.
  for (const std::vector<SceneGpu::Draw>* draws : {&scene.draws(), modules ? &scene.blended_draws() : nullptr}) {
    if (draws == nullptr) continue;
    for (const SceneGpu::Draw& draw : *draws) {
      const scene::Material& material = scene.materials()[static_cast<size_t>(draw.material)];
      const bool masked = material.alpha_tested();
      const bool skinned = draw.skin >= 0;
      const unsigned bits = material_features(material, untextured_variant) | (skinned ? features::skinned : 0) | motion;
      // Every variant a scene's materials need was compiled when the view was configured for it.
      const RasterProgram* program = !depth_only ? programs.gbuffer(bits, modules)
                                     : skinned   ? programs.skinned_depth(masked, modules)
                                     : masked    ? &masked_depth_program
                                                 : &depth_program;
      if (program == nullptr) {
        context.report_missing_program("g-buffer: a material's program was not prepared; its draws are skipped");
        continue;
      }
      use_program(*program, bound, projection);
      draw_one(context, *program, draw, bits, depth_only);
    }
  }
  end_draws();
}

// The blended materials over the presented image (forward.frag), farthest first by the centre of
// each draw's box: glTF sorts nothing within a mesh, and neither does this.
void blend_pass(const PassContext& context, bool srgb) {
  const SceneGpu& scene = context.scene;
  const std::vector<SceneGpu::Draw>& draws = scene.blended_draws();
  std::vector<std::pair<double, int>>& order = scene.blend_order();
  // By view-space z, most negative (farthest) first.
  for (size_t i = 0; i < draws.size(); ++i)
    order[i] = {(context.view.view * draws[i].world * glm::dvec4(draws[i].box_centre, 1.0)).z, static_cast<int>(i)};
  std::sort(order.begin(), order.end());
  const bool untextured_variant = context.targets.settings().untextured_variant;
  const glm::mat4 projection(context.view.projection);
  gl::api.Enable(GL_BLEND);
  gl::api.BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  gl::api.CullFace(GL_BACK);
  gl::api.ActiveTexture(GL_TEXTURE0 + unit_specular);
  gl::api.BindTexture(GL_TEXTURE_CUBE_MAP, scene.environment().specular.id());
  bind_texture(unit_brdf_lut, context.programs.brdf_lut);
  bind_texture(unit_linear_depth, context.targets.linear_depth);
  bind_texture(unit_joints, scene.joint_matrices());
  const RasterProgram* bound = nullptr;
  for (const auto& [key, index] : order) {
    const SceneGpu::Draw& draw = draws[static_cast<size_t>(index)];
    const unsigned bits =
        (material_features(scene.materials()[static_cast<size_t>(draw.material)], untextured_variant) & ~features::alpha_mask) |
        (draw.skin >= 0 ? features::skinned : 0);
    const RasterProgram* program = context.programs.forward(bits, srgb);
    if (program == nullptr) {  // prepared with the scene (prepare_material_programs)
      context.report_missing_program("blend: a blended material's program was not prepared; its draws are skipped");
      continue;
    }
    use_program(*program, bound, projection);
    draw_one(context, *program, draw, bits, false);
  }
  gl::api.Disable(GL_BLEND);
  gl::api.Disable(GL_CULL_FACE);
  end_draws();
  context.finish_pass(Pass::blend);
}

void begin_raster(const PassContext& context) {
  const FrameSettings& settings = context.targets.settings();
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, context.targets.gbuffer_fbo.id());
  gl::api.Viewport(0, 0, settings.width, settings.height);
  gl::api.Enable(GL_DEPTH_TEST);
  gl::api.CullFace(GL_BACK);
  gl::api.FrontFace(GL_CCW);
  const float zero[4] = {0, 0, 0, 0};
  const float one = 1.0f;
  gl::api.ClearBufferfv(GL_COLOR, 0, zero);
  gl::api.ClearBufferfv(GL_COLOR, 1, zero);
  gl::api.ClearBufferfv(GL_COLOR, 2, zero);  // linear depth 0 marks background
  const bool material = context.targets.material_attached();
  if (material) {
    const GLuint cleared[4] = {ViewTargets::kMaterialClearX, 0, 0, 0};
    gl::api.ClearBufferuiv(GL_COLOR, 3, cleared);
  }
  if (context.targets.modules()) gl::api.ClearBufferfv(GL_COLOR, material ? 4 : 3, zero);
  if (context.targets.motion_attached()) gl::api.ClearBufferfv(GL_COLOR, 4, zero);
  gl::api.DepthMask(GL_TRUE);
  gl::api.ClearBufferfv(GL_DEPTH, 0, &one);
}

// Blends this frame's AO into the reprojected average of the previous ones (temporal.comp).
void accumulate(const PassContext& context, bool moved) {
  ViewTargets& targets = context.targets;
  targets.temporal_params = pack_temporal_params(targets, context.view, moved);
  detail::update_uniform_buffer(targets.temporal_ubo, &targets.temporal_params, sizeof targets.temporal_params);

  const int previous = targets.history_current, next = 1 - previous;
  const bool motion = targets.motion_attached();
  gl::api.UseProgram((motion ? context.programs.temporal_motion : context.programs.temporal)->id());
  if (motion) bind_texture(4, targets.motion);
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
  context.finish_pass(Pass::temporal);
}

}  // namespace

bool follows_motion(const SceneGpu& scene, const FrameSettings& settings, bool modules) {
  if (!settings.temporal || !settings.motion_vectors || modules || scene.rig() == nullptr || scene.rig()->animations.empty())
    return false;
  // The motion target is the fifth: a GPU of four draw buffers (VideoCore VI) reprojects by the
  // camera alone, as before motion vectors.
  GLint draw_buffers = 0;
  gl::api.GetIntegerv(GL_MAX_DRAW_BUFFERS, &draw_buffers);
  return draw_buffers >= 5;
}

bool prepare_material_programs(Programs& programs, const SceneGpu& scene, const ViewTargets& targets, bool srgb_target,
                               std::string& error) {
  const FrameSettings& settings = targets.settings();
  const bool modules = targets.modules();
  // The variants draw_scene() picks: with the motion bit exactly where the targets have a motion target.
  const unsigned motion = targets.motion_attached() ? features::motion : 0;
  for (const scene::Material& material : scene.materials())
    if (!programs.prepare_gbuffer(material_features(material, settings.untextured_variant) | motion, modules, error))
      return false;
  // A skinned draw's variants besides (light field modules draw blended materials in the G-buffer).
  for (const std::vector<SceneGpu::Draw>* draws : {&scene.draws(), &scene.blended_draws()})
    for (const SceneGpu::Draw& draw : *draws) {
      if (draw.skin < 0) continue;
      const scene::Material& material = scene.materials()[static_cast<size_t>(draw.material)];
      if (!programs.prepare_skinned_depth(modules, error) ||
          !programs.prepare_gbuffer(material_features(material, settings.untextured_variant) | features::skinned | motion,
                                    modules, error))
        return false;
    }
  if (modules || settings.output != Picture::color) return true;
  for (const SceneGpu::Draw& draw : scene.blended_draws()) {
    const scene::Material& material = scene.materials()[static_cast<size_t>(draw.material)];
    const unsigned skinned = draw.skin >= 0 ? features::skinned : 0;
    if (!programs.prepare_forward((material_features(material, settings.untextured_variant) & ~features::alpha_mask) | skinned,
                                  srgb_target, error))
      return false;
  }
  return true;
}

void depth_prepass(const PassContext& context) {
  begin_raster(context);
  gl::api.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  gl::api.DepthFunc(GL_LESS);
  draw_scene(context, true);
  gl::api.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  context.finish_pass(Pass::depth_prepass);
}

void gbuffer_pass(const PassContext& context, bool after_prepass) {
  if (after_prepass) {
    gl::api.DepthFunc(GL_LEQUAL);
    gl::api.DepthMask(GL_FALSE);
  } else {
    begin_raster(context);
    gl::api.DepthFunc(GL_LESS);
  }
  draw_scene(context, false);
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
  context.finish_pass(Pass::gbuffer);
}

bool ao_passes(const PassContext& context) {
  ViewTargets& targets = context.targets;
  const FrameSettings& settings = targets.settings();
  const View& view = context.view;
  // A still view over a static scene sees the same AO: keep it rather than compute it again, once
  // the temporal average has all its frames. Light field modules share one set of targets, so each
  // module's AO is computed anew.
  const bool temporal = targets.temporal();
  // An animation that moved the scene is motion as much as a camera's: history is trusted for
  // fewer frames, and the AO is not kept.
  const bool still = targets.have_ao && view.view == targets.ao_view && view.projection == targets.ao_projection &&
                     context.scene.pose_version() == targets.ao_pose_version;
  targets.reused_ao =
      settings.reuse_static_ao && !view.module && still && (!temporal || targets.still_frames >= settings.history);
  if (targets.reused_ao) return false;
  const int w = settings.width, h = settings.height;
  const int ao_w = targets.ao_width(), ao_h = targets.ao_height();
  shared_layout::SsaoParams& params = targets.ssao_params;

  ssao::FrameView frame_view;
  frame_view.projection = glm::mat4(view.projection);
  const double centre_distance = glm::length(view.eye - context.scene.centre());
  frame_view.centre_depth = static_cast<float>(std::max(centre_distance, view.near));
  frame_view.nearest_depth = static_cast<float>(std::max(centre_distance - context.scene.radius(), view.near));
  frame_view.scene_radius = static_cast<float>(context.scene.radius());
  ssao::update_for_frame(params, settings.ao_settings, frame_view);
  if (temporal) ssao::advance_frame(params, targets.ao_frame);
  if (view.module) {
    // Algorithm 2 maps every sample itself and reads the full-resolution depth: no depth chain, and
    // no radius is skipped by a screen-space size that has no meaning here.
    params.first_radius = 0;
    params.end_radius = params.radius_count;
    for (glm::ivec4& level : params.levels) level.x = 0;
    params.skipped_radii_ao = 0.0f;
  }

  // Levels are only built when some radius in use reads one.
  int deepest = 0;
  for (int k = params.first_radius; k < params.end_radius; ++k) deepest = std::max(deepest, params.levels[k].x);
  if (deepest > 0) {
    gl::api.UseProgram(context.programs.depth_chain->id());
    bind_texture(0, targets.linear_depth);
    for (int level = 1; level <= deepest; ++level) {
      gl::api.Uniform1i(context.programs.depth_chain_source_level, level - 1);
      gl::api.BindImageTexture(0, targets.linear_depth.id(), level, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
      gl::api.DispatchCompute(groups(std::max(w >> level, 1), SSAO_GROUP_SIZE), groups(std::max(h >> level, 1), SSAO_GROUP_SIZE),
                              1);
      gl::api.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    context.finish_pass(Pass::depth_chain);
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
  context.finish_pass(Pass::ssao);

  if (temporal) accumulate(context, !still);

  if (settings.blur.mode != ssao::Blur::off) {
    const gl::Program& blur = settings.blur.mode == ssao::Blur::denoise     ? *context.programs.blur_denoise
                              : settings.blur.mode == ssao::Blur::bilateral ? *context.programs.blur_bilateral
                                                                            : *context.programs.blur_gaussian;
    gl::api.UseProgram(blur.id());
    bind_texture(1, targets.normal);  // read by denoise only
    const gl::Texture* sources[2] = {&targets.ao_unblurred(), &targets.ao_temp};
    const gl::Texture* destinations[2] = {&targets.ao_temp, &targets.ao_blurred};
    for (int direction = 0; direction < 2; ++direction) {
      gl::api.BindBufferBase(GL_UNIFORM_BUFFER, BINDING_BLUR_PARAMS, targets.blur_ubo[direction].id());
      bind_texture(0, *sources[direction]);
      gl::api.BindImageTexture(0, destinations[direction]->id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
      // A work group per run of pixels along the blur direction: x counts runs, y counts lines.
      if (direction == 0)
        gl::api.DispatchCompute(groups(ao_w, BLUR_GROUP_SIZE), static_cast<GLuint>(ao_h), 1);
      else
        gl::api.DispatchCompute(groups(ao_h, BLUR_GROUP_SIZE), static_cast<GLuint>(ao_w), 1);
      gl::api.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
      context.finish_pass(direction == 0 ? Pass::blur_h : Pass::blur_v);
    }
  }
  targets.still_frames = still ? std::min(targets.still_frames + 1, settings.history) : 1;
  targets.ao_view = view.view;
  targets.ao_projection = view.projection;
  targets.ao_far = view.far;
  targets.ao_pose_version = context.scene.pose_version();
  targets.have_ao = true;
  ++targets.ao_frame;
  return true;
}

namespace {

// covered_bounds.comp: per band of the view, the rectangle of tiles that holds the G-buffer's
// surfaces, for the present draw. They start each frame empty.
void find_covered_bounds(const PassContext& context) {
  ViewTargets& targets = context.targets;
  gl::api.BindBuffer(GL_SHADER_STORAGE_BUFFER, targets.covered_bounds.id());
  gl::api.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(targets.empty_bounds.size() * sizeof(GLuint)),
                        targets.empty_bounds.data());
  gl::api.BindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  gl::api.UseProgram(context.programs.covered_bounds->id());
  bind_texture(0, targets.linear_depth);
  gl::api.BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, targets.covered_bounds.id());
  constexpr int kGroup = 8;  // covered_bounds.comp's local size
  gl::api.DispatchCompute(static_cast<GLuint>((targets.tile_columns() + kGroup - 1) / kGroup),
                          static_cast<GLuint>((targets.tile_rows() + kGroup - 1) / kGroup), 1);
  gl::api.MemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT);
}

}  // namespace

void present_pass(const PassContext& context, const PresentTarget& target, float fade) {
  ViewTargets& targets = context.targets;
  const FrameSettings& settings = targets.settings();
  const View& view = context.view;
  const shared_layout::CompositeParams composite =
      pack_composite_params(targets, view, {target.x, target.y}, fade, context.scene);
  detail::update_uniform_buffer(targets.composite_ubo, &composite, sizeof composite);
  targets.last_inverse_far = composite.inverse_far;

  if (targets.present_tiles()) find_covered_bounds(context);
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, target.framebuffer);
  gl::api.Viewport(target.x, target.y, settings.width, settings.height);
  gl::api.Disable(GL_DEPTH_TEST);
  gl::api.Disable(GL_CULL_FACE);
  gl::api.BindBufferBase(GL_UNIFORM_BUFFER, BINDING_COMPOSITE_PARAMS, targets.composite_ubo.id());
  if (targets.present_tiles()) {
    gl::api.UseProgram(targets.present_background->id());
    gl::api.BindVertexArray(context.programs.empty_vertex_array.id());
    gl::api.DrawArrays(GL_TRIANGLES, 0, 3);
  }
  gl::api.UseProgram(targets.present_program->id());  // chosen for target.srgb at configure
  gl::api.BindBufferBase(GL_UNIFORM_BUFFER, BINDING_LIGHT_PARAMS, context.scene.lights().id());
  bind_texture(0, targets.albedo);
  bind_texture(1, targets.normal);
  bind_texture(2, targets.linear_depth);
  bind_texture(3, targets.ao_result());
  bind_texture(4, targets.material);
  gl::api.ActiveTexture(GL_TEXTURE5);
  gl::api.BindTexture(GL_TEXTURE_CUBE_MAP, context.scene.environment().specular.id());
  bind_texture(6, context.programs.brdf_lut);
  if (targets.present_tiles()) {
    constexpr float kTile = Programs::kPresentTile;
    gl::api.Uniform2f(targets.present_tile_scale, 2.0f * kTile / static_cast<float>(settings.width),
                      2.0f * kTile / static_cast<float>(settings.height));
    gl::api.BindVertexArray(targets.bounds_vertex_array.id());
    gl::api.DrawArraysInstanced(GL_TRIANGLES, 0, 6, targets.tile_bands());
  } else {
    gl::api.BindVertexArray(context.programs.empty_vertex_array.id());
    gl::api.DrawArrays(GL_TRIANGLES, 0, 3);
  }
  gl::api.BindVertexArray(0);
  // The debug outputs show the G-buffer and the AO, which blended surfaces are not part of.
  if (!view.module && settings.output == Picture::color && !context.scene.blended_draws().empty())
    blend_pass(context, target.srgb);
  // The next frame's compute passes store into the AO images this draw reads. A draw may still be
  // running (llvmpipe bins and rasterises it later) when a dispatch starts, and only this barrier
  // orders image stores after the texture fetches issued before it: without it, frames after the
  // first came out different from run to run.
  gl::api.MemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
  context.finish_pass(Pass::present);
}

void draw_view(const PassContext& context) {
  ViewTargets& targets = context.targets;
  const FrameSettings& settings = targets.settings();
  if (context.view.module) {
    const shared_layout::ModuleParams params = pack_module_params(*context.view.module);
    detail::update_uniform_buffer(targets.module_ubo, &params, sizeof params);
  }
  switch (settings.prepass) {
    case Prepass::on:
      targets.prepass_now = true;
      break;
    case Prepass::off:
      targets.prepass_now = false;
      break;
    case Prepass::automatic:  // first frame with, second without, then the faster of the two
      targets.prepass_now = targets.raster_with < 0.0      ? true
                            : targets.raster_without < 0.0 ? false
                                                           : targets.raster_with <= targets.raster_without;
      break;
  }
  if (targets.prepass_now) depth_prepass(context);
  gbuffer_pass(context, targets.prepass_now);
  if (settings.ao)
    ao_passes(context);
  else
    targets.reused_ao = false;
}

void render_view(const PassContext& context, const PresentTarget& target, float fade) {
  draw_view(context);
  present_pass(context, target, fade);
}

}  // namespace render
