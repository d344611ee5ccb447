#include "render/rotation.h"

#include "gl/gl_api.h"
#include "gl_util.h"

namespace render {

bool valid_rotation(int degrees, std::string& error) {
  if (degrees == 0 || degrees == 90 || degrees == 180 || degrees == 270) return true;
  error = "rotation: expected 0, 90, 180 or 270 (degrees clockwise), got " + std::to_string(degrees);
  return false;
}

bool Rotation::configure(Programs& programs, int degrees, int surface_width, int surface_height, bool surface_srgb,
                         std::string& error) {
  if (!valid_rotation(degrees, error)) return false;
  const bool quarter = degrees == 90 || degrees == 270;
  const int width = quarter ? surface_height : surface_width, height = quarter ? surface_width : surface_height;
  if (degrees == degrees_ && width == width_ && height == height_ && surface_srgb == srgb_ && (degrees == 0 || texture_))
    return true;
  degrees_ = degrees;
  width_ = width;
  height_ = height;
  surface_width_ = surface_width;
  surface_height_ = surface_height;
  srgb_ = surface_srgb;
  texture_ = {};
  framebuffer_ = {};
  if (degrees == 0) return true;
  if (!programs.build_rotate(error)) return false;
  // The same encoding as the surface, so the present pass writes it exactly as it would the surface.
  texture_ = detail::make_target(surface_srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, width, height);
  framebuffer_ = gl::make_framebuffer();
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
  gl::api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture_.id(), 0);
  const GLenum status = gl::api.CheckFramebufferStatus(GL_FRAMEBUFFER);
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, 0);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    error = "rotation: the " + std::to_string(width) + "x" + std::to_string(height) + " target is incomplete (0x" +
            std::to_string(status) + ")";
    texture_ = {};
    framebuffer_ = {};
    return false;
  }
  return true;
}

PresentTarget Rotation::target(const PresentTarget& surface) const {
  if (degrees_ == 0) return surface;
  return {framebuffer_.id(), 0, 0, srgb_};
}

void Rotation::finish(const Programs& programs, const PresentTarget& surface) const {
  if (degrees_ == 0) return;
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, surface.framebuffer);
  gl::api.Viewport(surface.x, surface.y, surface_width_, surface_height_);
  gl::api.Disable(GL_DEPTH_TEST);
  gl::api.Disable(GL_BLEND);
  gl::api.UseProgram(programs.rotate->id());
  gl::api.Uniform1i(programs.rotate_quarter_turns, degrees_ / 90);
  gl::api.ActiveTexture(GL_TEXTURE0);
  gl::api.BindTexture(GL_TEXTURE_2D, texture_.id());
  gl::api.BindVertexArray(programs.empty_vertex_array.id());
  gl::api.DrawArrays(GL_TRIANGLES, 0, 3);
  gl::api.BindVertexArray(0);
  gl::api.BindTexture(GL_TEXTURE_2D, 0);
  gl::api.UseProgram(0);
}

}  // namespace render
