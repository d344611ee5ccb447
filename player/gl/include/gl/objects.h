#pragma once
// Move-only owners of GL object names. A default-constructed object owns nothing ("no create"
// state), so members can be declared first and created once a context exists.
#include "gl/gl_api.h"

#include <utility>

namespace gl {

template <void (*Delete)(GLuint)>
class Object {
 public:
  Object() = default;
  explicit Object(GLuint id) : id_(id) {}
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;
  Object(Object&& other) noexcept : id_(std::exchange(other.id_, 0)) {}
  Object& operator=(Object&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, 0);
    }
    return *this;
  }
  ~Object() { reset(); }

  GLuint id() const { return id_; }
  explicit operator bool() const { return id_ != 0; }
  void reset() {
    if (id_ != 0) Delete(id_);
    id_ = 0;
  }

 private:
  GLuint id_ = 0;
};

namespace detail {
inline void delete_buffer(GLuint id) {
  api.DeleteBuffers(1, &id);
}
inline void delete_texture(GLuint id) {
  api.DeleteTextures(1, &id);
}
inline void delete_framebuffer(GLuint id) {
  api.DeleteFramebuffers(1, &id);
}
inline void delete_vertex_array(GLuint id) {
  api.DeleteVertexArrays(1, &id);
}
inline void delete_query(GLuint id) {
  api.DeleteQueries(1, &id);
}
inline void delete_program(GLuint id) {
  api.DeleteProgram(id);
}
inline void delete_shader(GLuint id) {
  api.DeleteShader(id);
}
}  // namespace detail

using Buffer = Object<detail::delete_buffer>;
using Texture = Object<detail::delete_texture>;
using Framebuffer = Object<detail::delete_framebuffer>;
using VertexArray = Object<detail::delete_vertex_array>;
using Query = Object<detail::delete_query>;
using Program = Object<detail::delete_program>;
using Shader = Object<detail::delete_shader>;

namespace detail {
// One name from a glGen* entry point, owned.
template <typename Owner, typename Generate>
Owner generate(Generate gen) {
  GLuint id = 0;
  gen(1, &id);
  return Owner(id);
}
}  // namespace detail

inline Buffer make_buffer() {
  return detail::generate<Buffer>(api.GenBuffers);
}
inline Texture make_texture() {
  return detail::generate<Texture>(api.GenTextures);
}
inline Framebuffer make_framebuffer() {
  return detail::generate<Framebuffer>(api.GenFramebuffers);
}
inline VertexArray make_vertex_array() {
  return detail::generate<VertexArray>(api.GenVertexArrays);
}
inline Query make_query() {
  return detail::generate<Query>(api.GenQueries);
}

}  // namespace gl
