#include "render/readback.h"

#include "gl_util.h"
#include "render/uniform_blocks.h"

#include <algorithm>
#include <cmath>

namespace render {
namespace {

std::vector<float> read_rgba_float(const gl::Texture& texture, int w, int h) {
  std::vector<float> pixels(static_cast<size_t>(w) * static_cast<size_t>(h) * 4);
  gl::Framebuffer fbo = gl::make_framebuffer();
  gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo.id());
  gl::api.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture.id(), 0);
  gl::api.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl::api.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl::api.ReadPixels(0, 0, w, h, GL_RGBA, GL_FLOAT, pixels.data());
  gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return pixels;
}

// gbuffer_normals.glsl's octahedron_decode, in the same float arithmetic.
glm::vec3 octahedron_decode(float x, float y) {
  glm::vec3 n(x, y, 1.0f - std::abs(x) - std::abs(y));
  if (n.z < 0.0f) {
    const float u = (1.0f - std::abs(n.y)) * (n.x >= 0.0f ? 1.0f : -1.0f);
    const float v = (1.0f - std::abs(n.x)) * (n.y >= 0.0f ? 1.0f : -1.0f);
    n.x = u;
    n.y = v;
  }
  return glm::normalize(n);
}

std::vector<glm::vec3> read_normal_pair(const ViewTargets& targets, int first_channel) {
  const std::vector<float> rgba = read_rgba_float(targets.normal, targets.settings().width, targets.settings().height);
  std::vector<glm::vec3> normals(rgba.size() / 4);
  for (size_t i = 0; i < normals.size(); ++i)
    normals[i] =
        octahedron_decode(rgba[i * 4 + static_cast<size_t>(first_channel)], rgba[i * 4 + static_cast<size_t>(first_channel) + 1]);
  return normals;
}

}  // namespace

std::vector<uint8_t> read_presented(const PresentTarget& target, int w, int h) {
  const size_t row = static_cast<size_t>(w) * 4;
  std::vector<uint8_t> pixels(row * static_cast<size_t>(h));
  gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, target.framebuffer);
  gl::api.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl::api.ReadPixels(target.x, target.y, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  std::vector<uint8_t> flipped(pixels.size());
  for (int y = 0; y < h; ++y)
    std::copy_n(pixels.begin() + static_cast<std::ptrdiff_t>(row * static_cast<size_t>(h - 1 - y)), row,
                flipped.begin() + static_cast<std::ptrdiff_t>(row * static_cast<size_t>(y)));
  return flipped;
}

std::vector<float> read_linear_depth(const ViewTargets& targets) {
  const std::vector<float> rgba = read_rgba_float(targets.linear_depth, targets.settings().width, targets.settings().height);
  std::vector<float> depth(rgba.size() / 4);
  for (size_t i = 0; i < depth.size(); ++i) depth[i] = rgba[i * 4];
  return depth;
}

std::vector<glm::vec3> read_view_normals(const ViewTargets& targets) {
  return read_normal_pair(targets, 0);
}
std::vector<glm::vec3> read_view_face_normals(const ViewTargets& targets) {
  return read_normal_pair(targets, 2);
}

std::vector<glm::vec3> read_motion(const ViewTargets& targets) {
  if (!targets.motion_attached()) return {};
  const std::vector<float> rgba = read_rgba_float(targets.motion, targets.settings().width, targets.settings().height);
  std::vector<glm::vec3> motion(rgba.size() / 4);
  for (size_t i = 0; i < motion.size(); ++i) motion[i] = glm::vec3(rgba[i * 4], rgba[i * 4 + 1], rgba[i * 4 + 2]);
  return motion;
}

std::vector<glm::vec2> read_ao(const gl::Texture& texture, int w, int h) {
  const std::vector<float> rgba = read_rgba_float(texture, w, h);
  std::vector<glm::vec2> ao(rgba.size() / 4);
  for (size_t i = 0; i < ao.size(); ++i) ao[i] = glm::vec2(rgba[i * 4], rgba[i * 4 + 1]);
  return ao;
}

std::vector<float> read_history_frames(const ViewTargets& targets) {
  if (!targets.temporal()) return {};
  const std::vector<float> rgba = read_rgba_float(targets.ao_unblurred(), targets.ao_width(), targets.ao_height());
  std::vector<float> frames(rgba.size() / 4);
  for (size_t i = 0; i < frames.size(); ++i) frames[i] = rgba[i * 4 + 2];
  return frames;
}

std::vector<glm::vec2> read_ao_full(const Programs& programs, const ViewTargets& targets) {
  const FrameSettings& settings = targets.settings();
  if (!settings.ao_settings.half_resolution) return read_ao(targets.ao_result(), targets.ao_width(), targets.ao_height());
  const int w = settings.width, h = settings.height;
  gl::Texture full = detail::make_target(GL_RGBA16F, w, h);
  const shared_layout::UpsampleParams params = pack_upsample_params(targets);
  gl::Buffer ubo = detail::make_uniform_buffer(&params, sizeof params);
  gl::api.UseProgram(programs.upsample->id());
  gl::api.BindBufferBase(GL_UNIFORM_BUFFER, BINDING_UPSAMPLE_PARAMS, ubo.id());
  detail::bind_texture(0, targets.ao_result());
  detail::bind_texture(1, targets.linear_depth);
  detail::bind_texture(2, targets.normal);
  gl::api.BindImageTexture(0, full.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
  gl::api.DispatchCompute(detail::groups(w, SSAO_GROUP_SIZE), detail::groups(h, SSAO_GROUP_SIZE), 1);
  gl::api.MemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
  return read_ao(full, w, h);
}

WorldSurface read_world_surface(const ViewTargets& targets, const View& view) {
  WorldSurface surface;
  surface.width = targets.settings().width;
  surface.height = targets.settings().height;
  const int w = surface.width, h = surface.height;
  const size_t count = static_cast<size_t>(w) * static_cast<size_t>(h);
  surface.depth = read_linear_depth(targets);
  const std::vector<glm::vec3> view_normals = read_view_normals(targets);
  const glm::dmat4& projection = view.projection;
  const glm::dmat4 inverse_view = glm::inverse(view.view);
  surface.position.assign(count * 4, 0.0f);
  surface.normal.assign(count * 4, 0.0f);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x);
      const double d = surface.depth[i];
      if (d <= 0.0) continue;  // background: alpha 0 marks it
      const double ndc_x = (x + 0.5) / w * 2.0 - 1.0, ndc_y = (y + 0.5) / h * 2.0 - 1.0;
      const glm::dvec4 view_position((ndc_x + projection[2][0]) * d / projection[0][0],
                                     (ndc_y + projection[2][1]) * d / projection[1][1], -d, 1.0);
      const glm::dvec3 world = glm::dvec3(inverse_view * view_position);
      const glm::dvec3 world_normal = glm::normalize(glm::dmat3(inverse_view) * glm::dvec3(view_normals[i]));
      for (int c = 0; c < 3; ++c) {
        surface.position[i * 4 + static_cast<size_t>(c)] = static_cast<float>(world[c]);
        surface.normal[i * 4 + static_cast<size_t>(c)] = static_cast<float>(world_normal[c]);
      }
      surface.position[i * 4 + 3] = surface.normal[i * 4 + 3] = 1.0f;
    }
  }
  return surface;
}

WorldSurface read_module_surface(const ViewTargets& targets) {
  WorldSurface surface;
  surface.width = targets.settings().width;
  surface.height = targets.settings().height;
  surface.position = read_rgba_float(targets.positions, surface.width, surface.height);
  surface.depth = read_linear_depth(targets);
  const std::vector<glm::vec3> normals = read_view_normals(targets);  // physical axes are the world's
  surface.normal.resize(normals.size() * 4);
  for (size_t i = 0; i < normals.size(); ++i) {
    const float object = surface.position[i * 4 + 3];
    for (int c = 0; c < 3; ++c) surface.normal[i * 4 + static_cast<size_t>(c)] = object > 0.0f ? normals[i][c] : 0.0f;
    surface.normal[i * 4 + 3] = object;
  }
  return surface;
}

}  // namespace render
