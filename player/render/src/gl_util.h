#pragma once
// Small GL helpers the render sources share.
#include "gl/objects.h"

#include <initializer_list>

namespace render::detail {

inline GLuint groups(int size, int group) {
  return static_cast<GLuint>((size + group - 1) / group);
}

gl::Texture make_target(GLenum format, int width, int height, int levels = 1);
gl::Buffer make_uniform_buffer(const void* data, GLsizeiptr size);
void update_uniform_buffer(const gl::Buffer& buffer, const void* data, GLsizeiptr size);
// Sampler uniforms are fixed to texture units once, so a frame only binds textures.
void assign_units(const gl::Program& program, std::initializer_list<const char*> samplers);
void bind_texture(int unit, const gl::Texture& texture);

}  // namespace render::detail
