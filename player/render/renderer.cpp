#include "render/renderer.h"

#include "gl/program.h"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace render {
namespace {

GLuint groups(int size, int group) { return static_cast<GLuint>((size + group - 1) / group); }

gl::Texture make_target(GLenum format, int width, int height, int levels = 1) {
  gl::Texture texture = gl::make_texture();
  gl::api.BindTexture(GL_TEXTURE_2D, texture.id());
  gl::api.TexStorage2D(GL_TEXTURE_2D, levels, format, width, height);
  // Every pass reads its inputs with texelFetch; a nearest filter (mipmapped where there are levels,
  // so texelFetch may address them) keeps the textures complete.
  gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
  gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  return texture;
}

gl::Buffer make_uniform_buffer(const void* data, GLsizeiptr size) {
  gl::Buffer buffer = gl::make_buffer();
  gl::api.BindBuffer(GL_UNIFORM_BUFFER, buffer.id());
  gl::api.BufferData(GL_UNIFORM_BUFFER, size, data, GL_DYNAMIC_DRAW);
  return buffer;
}

// Sampler uniforms are fixed to texture units once, so a frame only binds textures.
void assign_units(const gl::Program& program, std::initializer_list<const char*> samplers) {
  gl::api.UseProgram(program.id());
  int unit = 0;
  for (const char* sampler : samplers) gl::api.Uniform1i(gl::uniform(program, sampler), unit++);
}

void bind_texture(int unit, const gl::Texture& texture) {
  gl::api.ActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
  gl::api.BindTexture(GL_TEXTURE_2D, texture.id());
}

}  // namespace

std::string_view name(View view) {
  switch (view) {
    case View::color: return "color";
    case View::ao: return "ao";
    case View::normal: return "normal";
    case View::depth: return "depth";
  }
  return "?";
}

std::string_view name(Prepass prepass) {
  switch (prepass) {
    case Prepass::off: return "off";
    case Prepass::on: return "on";
    case Prepass::automatic: return "auto";
  }
  return "?";
}

std::string_view pass_name(int pass) {
  switch (pass) {
    case kDepthPrepass: return "depth prepass";
    case kGBuffer: return "g-buffer";
    case kDepthChain: return "depth chain";
    case kSsao: return "ssao";
    case kBlurH: return "blur horizontal";
    case kBlurV: return "blur vertical";
    case kUpsample: return "upsample";
    case kComposite: return "composite";
    default: return "?";
  }
}

bool Renderer::build_gbuffer_program(GBufferProgram& out, const std::string& fragment, const std::string& defines,
                                     std::string& error) {
  out.program = gl::build_program({{GL_VERTEX_SHADER, "gbuffer.vert"}, {GL_FRAGMENT_SHADER, fragment}}, defines, error);
  if (!out.program) return false;
  out.model_view = gl::uniform(out.program, "u_model_view");
  out.projection = gl::uniform(out.program, "u_projection");
  out.normal_matrix = gl::uniform(out.program, "u_normal_matrix");
  out.base_color = gl::uniform(out.program, "u_base_color");
  out.texture = gl::uniform(out.program, "u_base_color_texture");
  return true;
}

bool Renderer::init(const gl::Caps& caps, std::string& error) {
  caps_ = caps;
  if (!build_gbuffer_program(gbuffer_plain_, "gbuffer.frag", "", error)) return false;
  if (!build_gbuffer_program(gbuffer_textured_, "gbuffer.frag", "#define HAS_BASECOLOR_TEXTURE 1\n", error)) return false;
  if (!build_gbuffer_program(depth_only_, "depth_only.frag", "", error)) return false;
  depth_chain_ = gl::build_program({{GL_COMPUTE_SHADER, "depth_chain.comp"}}, "", error);
  if (!depth_chain_) return false;
  depth_chain_source_level_ = gl::uniform(depth_chain_, "u_source_level");
  upsample_ = gl::build_program({{GL_COMPUTE_SHADER, "upsample.comp"}}, "", error);
  if (!upsample_) return false;
  blur_gaussian_ = gl::build_program({{GL_COMPUTE_SHADER, "blur.comp"}}, "", error);
  if (!blur_gaussian_) return false;
  blur_bilateral_ = gl::build_program({{GL_COMPUTE_SHADER, "blur.comp"}}, "#define BILATERAL 1\n", error);
  if (!blur_bilateral_) return false;
  composite_ = gl::build_program({{GL_COMPUTE_SHADER, "composite.comp"}}, "", error);
  if (!composite_) return false;
  assign_units(depth_chain_, {"u_linear_depth"});
  assign_units(upsample_, {"u_ao", "u_linear_depth"});
  assign_units(blur_gaussian_, {"u_source"});
  assign_units(blur_bilateral_, {"u_source"});
  assign_units(composite_, {"u_albedo", "u_normal", "u_linear_depth", "u_ao"});
  gl::api.UseProgram(0);
  white_ = gl::make_texture();
  gl::api.BindTexture(GL_TEXTURE_2D, white_.id());
  gl::api.TexStorage2D(GL_TEXTURE_2D, 1, GL_SRGB8_ALPHA8, 1, 1);
  const uint8_t white_texel[4] = {255, 255, 255, 255};
  gl::api.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl::api.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, white_texel);
  gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl::api.BindTexture(GL_TEXTURE_2D, 0);
  timer_.create(caps.timer_query);
  return true;
}

bool Renderer::upload(const scene::Scene& scene, std::string& error) {
  meshes_.clear();
  textures_.clear();
  draws_.clear();
  materials_ = scene.materials;
  for (const scene::Mesh& mesh : scene.meshes) {
    GpuMesh gpu;
    gpu.vao = gl::make_vertex_array();
    gl::api.BindVertexArray(gpu.vao.id());
    gpu.vertices = gl::make_buffer();
    gl::api.BindBuffer(GL_ARRAY_BUFFER, gpu.vertices.id());
    gl::api.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(scene::Vertex)),
                       mesh.vertices.data(), GL_STATIC_DRAW);
    gpu.indices = gl::make_buffer();
    gl::api.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu.indices.id());
    gl::api.BufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.indices.size() * sizeof(uint32_t)),
                       mesh.indices.data(), GL_STATIC_DRAW);
    constexpr auto stride = static_cast<GLsizei>(sizeof(scene::Vertex));
    gl::api.EnableVertexAttribArray(0);
    gl::api.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(scene::Vertex, position)));
    gl::api.EnableVertexAttribArray(1);
    gl::api.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(scene::Vertex, normal)));
    gl::api.EnableVertexAttribArray(2);
    gl::api.VertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(scene::Vertex, uv)));
    gpu.index_count = static_cast<GLsizei>(mesh.indices.size());
    meshes_.push_back(std::move(gpu));
  }
  gl::api.BindVertexArray(0);
  for (const scene::Texture& source : scene.textures) {
    if (source.width > caps_.max_texture_size || source.height > caps_.max_texture_size) {
      error = "texture of " + std::to_string(source.width) + "x" + std::to_string(source.height) +
              " exceeds the GPU's limit of " + std::to_string(caps_.max_texture_size);
      return false;
    }
    gl::Texture texture = gl::make_texture();
    gl::api.BindTexture(GL_TEXTURE_2D, texture.id());
    const int levels = source.mipmaps ? 1 + static_cast<int>(std::floor(std::log2(std::max(source.width, source.height)))) : 1;
    gl::api.TexStorage2D(GL_TEXTURE_2D, levels, GL_SRGB8_ALPHA8, source.width, source.height);
    gl::api.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl::api.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, source.width, source.height, GL_RGBA, GL_UNSIGNED_BYTE, source.rgba.data());
    if (levels > 1) gl::api.GenerateMipmap(GL_TEXTURE_2D);
    gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
    gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, source.mag == scene::Filter::nearest ? GL_NEAREST : GL_LINEAR);
    gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, source.repeat_s ? GL_REPEAT : GL_CLAMP_TO_EDGE);
    gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, source.repeat_t ? GL_REPEAT : GL_CLAMP_TO_EDGE);
    textures_.push_back(std::move(texture));
  }
  for (const scene::Instance& instance : scene.instances)
    draws_.push_back({instance.mesh, scene.meshes[static_cast<size_t>(instance.mesh)].material, instance.world});
  std::stable_sort(draws_.begin(), draws_.end(), [&](const Draw& a, const Draw& b) {
    return (materials_[static_cast<size_t>(a.material)].base_color_texture >= 0) <
           (materials_[static_cast<size_t>(b.material)].base_color_texture >= 0);
  });
  scene_radius_ = scene.bounds.radius();
  scene_centre_ = scene.bounds.centre();
  const GLenum status = gl::api.GetError();
  if (status != GL_NO_ERROR) {
    error = "uploading the scene raised GL error 0x" + std::to_string(status);
    return false;
  }
  return true;
}

bool Renderer::configure(const FrameSettings& settings, std::string& error) {
  if (settings.width < 1 || settings.height < 1 || settings.width > caps_.max_texture_size ||
      settings.height > caps_.max_texture_size) {
    error = "--size: " + std::to_string(settings.width) + "x" + std::to_string(settings.height) +
            " is outside 1.." + std::to_string(caps_.max_texture_size) + " per side";
    return false;
  }
  settings_ = settings;
  gl_error_.clear();
  have_ao_ = reused_ao_ = false;
  raster_with_ = raster_without_ = -1.0;
  const int w = settings.width, h = settings.height;
  std::string defines = "#define ESTIMATOR " + std::to_string(static_cast<int>(settings.ao_settings.estimator)) + "\n";
  ssao_ = gl::build_program({{GL_COMPUTE_SHADER, "ssao.comp"}}, defines, error);
  if (!ssao_) return false;
  ssao_inverse_far_ = gl::uniform(ssao_, "u_inverse_far");
  assign_units(ssao_, {"u_linear_depth", "u_normal"});
  gl::api.UseProgram(0);

  base_radius_ = settings.radius > 0.0f ? settings.radius : static_cast<float>(0.1 * scene_radius_);
  ssao_params_ = ssao::make_ssao_params(settings.ao_settings, base_radius_, w, h);
  const int ao_w = ssao_params_.counts.z, ao_h = ssao_params_.counts.w;
  depth_levels_ = ssao::depth_chain_levels(w, h);
  albedo_ = make_target(GL_RGBA8, w, h);
  normal_ = make_target(GL_RGBA16F, w, h);
  linear_depth_ = make_target(GL_R32F, w, h, depth_levels_);
  depth_ = make_target(GL_DEPTH_COMPONENT32F, w, h);
  ao_raw_ = make_target(GL_RGBA16F, ao_w, ao_h);
  ao_temp_ = make_target(GL_RGBA16F, ao_w, ao_h);
  ao_blurred_ = make_target(GL_RGBA16F, ao_w, ao_h);
  ao_full_ = settings.ao_settings.half_resolution ? make_target(GL_RGBA16F, w, h) : gl::Texture();
  output_ = make_target(GL_RGBA8, w, h);

  gbuffer_fbo_ = gl::make_framebuffer();
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, gbuffer_fbo_.id());
  gl::api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, albedo_.id(), 0);
  gl::api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, normal_.id(), 0);
  gl::api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT2, GL_TEXTURE_2D, linear_depth_.id(), 0);
  gl::api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, depth_.id(), 0);
  const GLenum buffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2};
  gl::api.DrawBuffers(3, buffers);
  const GLenum status = gl::api.CheckFramebufferStatus(GL_FRAMEBUFFER);
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    error = "the G-buffer framebuffer is incomplete (status 0x" + std::to_string(status) + ")";
    return false;
  }
  read_fbo_ = gl::make_framebuffer();

  // The projection and the radii in use change with the camera; render() refreshes them.
  ssao_ubo_ = make_uniform_buffer(&ssao_params_, sizeof ssao_params_);
  for (int direction = 0; direction < 2; ++direction) {
    blur_params_[direction] = ssao::make_blur_params(settings.blur, direction, ao_w, ao_h);
    blur_ubo_[direction] = make_uniform_buffer(&blur_params_[direction], sizeof blur_params_[direction]);
  }
  upsample_params_.config = glm::ivec4(w, h, ao_w, ao_h);
  upsample_ubo_ = make_uniform_buffer(&upsample_params_, sizeof upsample_params_);
  shared_layout::CompositeParams composite{};
  composite_ubo_ = make_uniform_buffer(&composite, sizeof composite);
  const GLenum gl_status = gl::api.GetError();
  if (gl_status != GL_NO_ERROR) {
    error = "allocating render targets raised GL error 0x" + std::to_string(gl_status);
    return false;
  }
  return true;
}

void Renderer::check(int pass) {
  if (!settings_.check_errors) return;
  const GLenum status = gl::api.GetError();
  if (status != GL_NO_ERROR && gl_error_.empty()) {
    char text[96];
    std::snprintf(text, sizeof text, "%s: GL error 0x%04x", pass_name(pass).data(), status);
    gl_error_ = text;  // only the first error is kept; the string's capacity suffices after the first frame
  }
}

void Renderer::draw_scene(bool depth_only, const glm::dmat4& view, const glm::mat4& projection) {
  const GBufferProgram* bound = nullptr;
  for (const Draw& draw : draws_) {
    const scene::Material& material = materials_[static_cast<size_t>(draw.material)];
    const bool textured = material.base_color_texture >= 0;
    const bool fetches = textured || !settings_.untextured_variant;
    const GBufferProgram* program = depth_only ? &depth_only_ : fetches ? &gbuffer_textured_ : &gbuffer_plain_;
    if (program != bound) {
      gl::api.UseProgram(program->program.id());
      gl::api.UniformMatrix4fv(program->projection, 1, GL_FALSE, glm::value_ptr(projection));
      if (program->texture >= 0) gl::api.Uniform1i(program->texture, 0);
      bound = program;
    }
    // Composed in double, then rounded: positions reach the GPU relative to the camera.
    const glm::mat4 model_view(view * draw.world);
    const glm::mat3 normal_matrix(glm::transpose(glm::inverse(glm::dmat3(view * draw.world))));
    gl::api.UniformMatrix4fv(program->model_view, 1, GL_FALSE, glm::value_ptr(model_view));
    if (!depth_only) {
      gl::api.UniformMatrix3fv(program->normal_matrix, 1, GL_FALSE, glm::value_ptr(normal_matrix));
      gl::api.Uniform4fv(program->base_color, 1, glm::value_ptr(material.base_color));
      if (fetches) {
        gl::api.ActiveTexture(GL_TEXTURE0);
        gl::api.BindTexture(GL_TEXTURE_2D, textured ? textures_[static_cast<size_t>(material.base_color_texture)].id() : white_.id());
      }
    }
    if (material.double_sided) gl::api.Disable(GL_CULL_FACE);
    else gl::api.Enable(GL_CULL_FACE);
    const GpuMesh& mesh = meshes_[static_cast<size_t>(draw.mesh)];
    gl::api.BindVertexArray(mesh.vao.id());
    gl::api.DrawElements(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr);
  }
  gl::api.BindVertexArray(0);
}

void Renderer::render(const scene::Camera& camera) {
  const int w = settings_.width, h = settings_.height;
  const glm::dmat4 view = camera.view();
  const glm::mat4 projection(camera.projection());
  inverse_far_ = static_cast<float>(1.0 / camera.far);
  timer_.begin();

  gl::api.BindFramebuffer(GL_FRAMEBUFFER, gbuffer_fbo_.id());
  gl::api.Viewport(0, 0, w, h);
  gl::api.Enable(GL_DEPTH_TEST);
  gl::api.CullFace(GL_BACK);
  gl::api.FrontFace(GL_CCW);
  const float zero[4] = {0, 0, 0, 0};
  const float one = 1.0f;
  gl::api.ClearBufferfv(GL_COLOR, 0, zero);
  gl::api.ClearBufferfv(GL_COLOR, 1, zero);
  gl::api.ClearBufferfv(GL_COLOR, 2, zero);  // linear depth 0 marks background
  gl::api.DepthMask(GL_TRUE);
  gl::api.ClearBufferfv(GL_DEPTH, 0, &one);

  switch (settings_.prepass) {
    case Prepass::on: prepass_now_ = true; break;
    case Prepass::off: prepass_now_ = false; break;
    case Prepass::automatic:  // first frame with, second without, then the faster of the two
      prepass_now_ = raster_with_ < 0.0 ? true : raster_without_ < 0.0 ? false : raster_with_ <= raster_without_;
      break;
  }
  if (prepass_now_) {
    gl::api.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl::api.DepthFunc(GL_LESS);
    draw_scene(true, view, projection);
    gl::api.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    check(kDepthPrepass);
    timer_.mark(kDepthPrepass);
    gl::api.DepthFunc(GL_LEQUAL);
    gl::api.DepthMask(GL_FALSE);
  } else {
    gl::api.DepthFunc(GL_LESS);
  }
  draw_scene(false, view, projection);
  gl::api.DepthMask(GL_TRUE);
  gl::api.Disable(GL_DEPTH_TEST);
  gl::api.Disable(GL_CULL_FACE);
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, 0);
  check(kGBuffer);
  timer_.mark(kGBuffer);

  const bool half = settings_.ao_settings.half_resolution;
  const gl::Texture* ao_result = half ? &ao_full_ : settings_.blur.mode != ssao::Blur::off ? &ao_blurred_ : &ao_raw_;
  const glm::dmat4 projection_d = camera.projection();
  // A still camera over a static scene sees the same AO: keep it rather than compute it again.
  reused_ao_ = settings_.ao && settings_.reuse_static_ao && have_ao_ && view == last_view_ && projection_d == last_projection_;
  if (settings_.ao && !reused_ao_) {
    const int ao_w = ssao_params_.counts.z, ao_h = ssao_params_.counts.w;
    ssao::FrameView frame_view;
    frame_view.projection = projection;
    const double centre_distance = glm::length(camera.eye - scene_centre_);
    frame_view.centre_depth = static_cast<float>(std::max(centre_distance, camera.near));
    frame_view.nearest_depth = static_cast<float>(std::max(centre_distance - scene_radius_, camera.near));
    frame_view.scene_radius = static_cast<float>(scene_radius_);
    ssao::update_for_frame(ssao_params_, settings_.ao_settings, frame_view);

    // Levels are only built when some radius in use reads one.
    int deepest = 0;
    for (int k = ssao_params_.radius_range.x; k < ssao_params_.radius_range.y; ++k)
      deepest = std::max(deepest, k < 4 ? ssao_params_.lods_0_3[k] : ssao_params_.config.x);
    if (deepest > 0) {
      gl::api.UseProgram(depth_chain_.id());
      bind_texture(0, linear_depth_);
      for (int level = 1; level <= deepest; ++level) {
        gl::api.Uniform1i(depth_chain_source_level_, level - 1);
        gl::api.BindImageTexture(0, linear_depth_.id(), level, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
        gl::api.DispatchCompute(groups(std::max(w >> level, 1), SSAO_GROUP_SIZE),
                                groups(std::max(h >> level, 1), SSAO_GROUP_SIZE), 1);
        gl::api.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
      }
      check(kDepthChain);
      timer_.mark(kDepthChain);
    }

    gl::api.BindBuffer(GL_UNIFORM_BUFFER, ssao_ubo_.id());
    gl::api.BufferSubData(GL_UNIFORM_BUFFER, 0, sizeof ssao_params_, &ssao_params_);
    gl::api.UseProgram(ssao_.id());
    gl::api.BindBufferBase(GL_UNIFORM_BUFFER, BINDING_SSAO_PARAMS, ssao_ubo_.id());
    gl::api.Uniform1f(ssao_inverse_far_, inverse_far_);
    bind_texture(0, linear_depth_);
    bind_texture(1, normal_);
    gl::api.BindImageTexture(0, ao_raw_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    gl::api.DispatchCompute(groups(ao_w, SSAO_GROUP_SIZE), groups(ao_h, SSAO_GROUP_SIZE), 1);
    gl::api.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    check(kSsao);
    timer_.mark(kSsao);

    const gl::Texture* ao_low = &ao_raw_;
    if (settings_.blur.mode != ssao::Blur::off) {
      const gl::Program& blur = settings_.blur.mode == ssao::Blur::bilateral ? blur_bilateral_ : blur_gaussian_;
      gl::api.UseProgram(blur.id());
      const gl::Texture* sources[2] = {&ao_raw_, &ao_temp_};
      const gl::Texture* targets[2] = {&ao_temp_, &ao_blurred_};
      for (int direction = 0; direction < 2; ++direction) {
        gl::api.BindBufferBase(GL_UNIFORM_BUFFER, BINDING_BLUR_PARAMS, blur_ubo_[direction].id());
        bind_texture(0, *sources[direction]);
        gl::api.BindImageTexture(0, targets[direction]->id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
        // A work group per run of pixels along the blur direction: x counts runs, y counts lines.
        if (direction == 0) gl::api.DispatchCompute(groups(ao_w, BLUR_GROUP_SIZE), static_cast<GLuint>(ao_h), 1);
        else gl::api.DispatchCompute(groups(ao_h, BLUR_GROUP_SIZE), static_cast<GLuint>(ao_w), 1);
        gl::api.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        check(direction == 0 ? kBlurH : kBlurV);
        timer_.mark(direction == 0 ? kBlurH : kBlurV);
      }
      ao_low = &ao_blurred_;
    }

    if (half) {
      upsample_params_.depth = glm::vec4(inverse_far_, 0.0f, 0.0f, 0.0f);
      gl::api.BindBuffer(GL_UNIFORM_BUFFER, upsample_ubo_.id());
      gl::api.BufferSubData(GL_UNIFORM_BUFFER, 0, sizeof upsample_params_, &upsample_params_);
      gl::api.UseProgram(upsample_.id());
      gl::api.BindBufferBase(GL_UNIFORM_BUFFER, BINDING_UPSAMPLE_PARAMS, upsample_ubo_.id());
      bind_texture(0, *ao_low);
      bind_texture(1, linear_depth_);
      gl::api.BindImageTexture(0, ao_full_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
      gl::api.DispatchCompute(groups(w, SSAO_GROUP_SIZE), groups(h, SSAO_GROUP_SIZE), 1);
      gl::api.MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
      check(kUpsample);
      timer_.mark(kUpsample);
    }
    last_view_ = view;
    last_projection_ = projection_d;
    have_ao_ = true;
  }

  shared_layout::CompositeParams composite{};
  composite.light_direction = glm::vec4(glm::normalize(glm::vec3(-0.4f, 0.6f, 0.7f)), 0.35f);
  composite.background = glm::vec4(0.05f, 0.06f, 0.08f, 1.0f);
  composite.depth_range = glm::vec4(static_cast<float>(camera.near), static_cast<float>(camera.far), 0.0f, 0.0f);
  composite.config = glm::ivec4(static_cast<int>(settings_.view), settings_.ao ? 1 : 0, w, h);
  gl::api.BindBuffer(GL_UNIFORM_BUFFER, composite_ubo_.id());
  gl::api.BufferSubData(GL_UNIFORM_BUFFER, 0, sizeof composite, &composite);
  gl::api.UseProgram(composite_.id());
  gl::api.BindBufferBase(GL_UNIFORM_BUFFER, BINDING_COMPOSITE_PARAMS, composite_ubo_.id());
  bind_texture(0, albedo_);
  bind_texture(1, normal_);
  bind_texture(2, linear_depth_);
  bind_texture(3, *ao_result);
  gl::api.BindImageTexture(0, output_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA8);
  gl::api.DispatchCompute(groups(w, SSAO_GROUP_SIZE), groups(h, SSAO_GROUP_SIZE), 1);
  gl::api.MemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_PIXEL_BUFFER_BARRIER_BIT);
  check(kComposite);
  timer_.mark(kComposite);
}

PassTimes Renderer::collect_times() {
  PassTimes times;
  const auto ms = timer_.collect();
  for (int pass = 0; pass < kPassCount; ++pass) times.ms[static_cast<size_t>(pass)] = ms[static_cast<size_t>(pass)];
  times.gpu_timed = timer_.gpu_timed();
  if (settings_.prepass == Prepass::automatic && (raster_with_ < 0.0 || raster_without_ < 0.0)) {
    const double raster = std::max(0.0, times.ms[kDepthPrepass]) + std::max(0.0, times.ms[kGBuffer]);
    (prepass_now_ ? raster_with_ : raster_without_) = raster;
  }
  return times;
}

std::vector<float> Renderer::read_rgba_float(const gl::Texture& texture, int w, int h) const {
  std::vector<float> pixels(static_cast<size_t>(w) * static_cast<size_t>(h) * 4);
  gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, read_fbo_.id());
  gl::api.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture.id(), 0);
  gl::api.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl::api.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl::api.ReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, pixels.data());
  gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return pixels;
}

std::vector<uint8_t> Renderer::read_color() const {
  const int w = settings_.width, h = settings_.height;
  const size_t row = static_cast<size_t>(w) * 4;
  std::vector<uint8_t> pixels(row * static_cast<size_t>(h));
  gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, read_fbo_.id());
  gl::api.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, output_.id(), 0);
  gl::api.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl::api.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl::api.ReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  std::vector<uint8_t> flipped(pixels.size());
  for (int y = 0; y < h; ++y)
    std::copy_n(pixels.begin() + static_cast<std::ptrdiff_t>(row * static_cast<size_t>(h - 1 - y)), row,
                flipped.begin() + static_cast<std::ptrdiff_t>(row * static_cast<size_t>(y)));
  return flipped;
}

std::vector<float> Renderer::read_linear_depth() const {
  const std::vector<float> rgba = read_rgba_float(linear_depth_, settings_.width, settings_.height);
  std::vector<float> depth(rgba.size() / 4);
  for (size_t i = 0; i < depth.size(); ++i) depth[i] = rgba[i * 4];
  return depth;
}

std::vector<glm::vec3> Renderer::read_view_normals() const {
  const std::vector<float> rgba = read_rgba_float(normal_, settings_.width, settings_.height);
  std::vector<glm::vec3> normals(rgba.size() / 4);
  for (size_t i = 0; i < normals.size(); ++i) normals[i] = glm::vec3(rgba[i * 4], rgba[i * 4 + 1], rgba[i * 4 + 2]);
  return normals;
}

std::vector<glm::vec2> Renderer::read_ao(const gl::Texture& texture, int w, int h) const {
  const std::vector<float> rgba = read_rgba_float(texture, w, h);
  std::vector<glm::vec2> ao(rgba.size() / 4);
  for (size_t i = 0; i < ao.size(); ++i) ao[i] = glm::vec2(rgba[i * 4], rgba[i * 4 + 1]);
  return ao;
}

std::vector<glm::vec2> Renderer::read_ao_raw() const { return read_ao(ao_raw_, ssao_params_.counts.z, ssao_params_.counts.w); }

std::vector<glm::vec2> Renderer::read_ao_blurred() const {
  return read_ao(settings_.blur.mode == ssao::Blur::off ? ao_raw_ : ao_blurred_, ssao_params_.counts.z, ssao_params_.counts.w);
}

std::vector<glm::vec2> Renderer::read_ao_final() const {
  if (settings_.ao_settings.half_resolution) return read_ao(ao_full_, settings_.width, settings_.height);
  return read_ao_blurred();
}

}  // namespace render
