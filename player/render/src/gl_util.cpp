#include "gl_util.h"

#include "gl/program.h"

namespace render::detail {

gl::Texture make_target(GLenum format, int width, int height, int levels) {
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

void update_uniform_buffer(const gl::Buffer& buffer, const void* data, GLsizeiptr size) {
  gl::api.BindBuffer(GL_UNIFORM_BUFFER, buffer.id());
  gl::api.BufferSubData(GL_UNIFORM_BUFFER, 0, size, data);
}

void assign_units(const gl::Program& program, std::initializer_list<const char*> samplers) {
  gl::api.UseProgram(program.id());
  int unit = 0;
  for (const char* sampler : samplers) gl::api.Uniform1i(gl::uniform(program, sampler), unit++);
}

void bind_texture(int unit, const gl::Texture& texture) {
  gl::api.ActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
  gl::api.BindTexture(GL_TEXTURE_2D, texture.id());
}

}  // namespace render::detail
