#include "render/scene_gpu.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace render {
namespace {

// The smallest slice worth a call: below this the per-call overhead dominates.
constexpr size_t kMinSlice = 64 * 1024;

size_t vertex_bytes(const scene::Mesh& mesh) {
  return mesh.vertices.size() * sizeof(scene::Vertex);
}
size_t index_bytes(const scene::Mesh& mesh) {
  return mesh.indices.size() * sizeof(uint32_t);
}

SceneGpu::Mesh allocate_mesh(const scene::Mesh& mesh) {
  SceneGpu::Mesh gpu;
  gpu.vao = gl::make_vertex_array();
  gl::api.BindVertexArray(gpu.vao.id());
  gpu.vertices = gl::make_buffer();
  gl::api.BindBuffer(GL_ARRAY_BUFFER, gpu.vertices.id());
  gl::api.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(vertex_bytes(mesh)), nullptr, GL_STATIC_DRAW);
  gpu.indices = gl::make_buffer();
  gl::api.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu.indices.id());
  gl::api.BufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(index_bytes(mesh)), nullptr, GL_STATIC_DRAW);
  constexpr auto stride = static_cast<GLsizei>(sizeof(scene::Vertex));
  gl::api.EnableVertexAttribArray(0);
  gl::api.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(scene::Vertex, position)));
  gl::api.EnableVertexAttribArray(1);
  gl::api.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(scene::Vertex, normal)));
  gl::api.EnableVertexAttribArray(2);
  gl::api.VertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(scene::Vertex, uv)));
  gl::api.BindVertexArray(0);
  gpu.index_count = static_cast<GLsizei>(mesh.indices.size());
  return gpu;
}

// Uploads bytes [from, to) of a buffer's data. GL_COPY_WRITE_BUFFER leaves the VAO's element
// binding alone.
void upload_range(const gl::Buffer& buffer, const void* data, size_t from, size_t to) {
  if (to <= from) return;
  gl::api.BindBuffer(GL_COPY_WRITE_BUFFER, buffer.id());
  gl::api.BufferSubData(GL_COPY_WRITE_BUFFER, static_cast<GLintptr>(from), static_cast<GLsizeiptr>(to - from),
                        static_cast<const unsigned char*>(data) + from);
}

int mip_levels(const scene::Texture& texture) {
  return texture.mipmaps ? 1 + static_cast<int>(std::floor(std::log2(std::max(texture.width, texture.height)))) : 1;
}

}  // namespace

void SceneGpu::begin(std::shared_ptr<const scene::Scene> scene, const gl::Caps& caps) {
  source_ = std::move(scene);
  max_texture_size_ = caps.max_texture_size;
  mesh_cursor_ = texture_cursor_ = offset_ = 0;
  ready_ = false;
  error_.clear();
  meshes_.clear();
  textures_.clear();
  draws_.clear();
  materials_ = source_->materials;
  bytes_ = 0;
}

bool SceneGpu::step(size_t budget_bytes) {
  if (ready_ || failed()) return true;
  const scene::Scene& scene = *source_;
  size_t spent = 0;
  while (spent == 0 || spent < budget_bytes) {
    const size_t slice = std::max(kMinSlice, budget_bytes > spent ? budget_bytes - spent : 0);
    if (mesh_cursor_ < scene.meshes.size()) {
      const scene::Mesh& mesh = scene.meshes[mesh_cursor_];
      if (offset_ == 0) meshes_.push_back(allocate_mesh(mesh));
      const Mesh& gpu = meshes_.back();
      const size_t vbytes = vertex_bytes(mesh), total = vbytes + index_bytes(mesh);
      const size_t end = std::min(total, offset_ + slice);
      upload_range(gpu.vertices, mesh.vertices.data(), std::min(offset_, vbytes), std::min(end, vbytes));
      upload_range(gpu.indices, mesh.indices.data(), std::max(offset_, vbytes) - vbytes, std::max(end, vbytes) - vbytes);
      spent += end - offset_;
      offset_ = end;
      if (offset_ >= total) {
        ++mesh_cursor_;
        offset_ = 0;
      }
    } else if (texture_cursor_ < scene.textures.size()) {
      const scene::Texture& source = scene.textures[texture_cursor_];
      if (offset_ == 0) {
        if (source.width > max_texture_size_ || source.height > max_texture_size_) {
          source_.reset();
          error_ = "texture " + std::to_string(texture_cursor_) + " of " + std::to_string(source.width) + "x" +
                   std::to_string(source.height) + " exceeds the GPU's limit of " + std::to_string(max_texture_size_);
          return true;
        }
        gl::Texture texture = gl::make_texture();
        gl::api.BindTexture(GL_TEXTURE_2D, texture.id());
        gl::api.TexStorage2D(GL_TEXTURE_2D, mip_levels(source), GL_SRGB8_ALPHA8, source.width, source.height);
        textures_.push_back(std::move(texture));
      }
      const size_t row_bytes = static_cast<size_t>(source.width) * 4;
      const size_t rows = std::min(static_cast<size_t>(source.height) - offset_, std::max<size_t>(1, slice / row_bytes));
      gl::api.BindTexture(GL_TEXTURE_2D, textures_.back().id());
      gl::api.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
      gl::api.TexSubImage2D(GL_TEXTURE_2D, 0, 0, static_cast<GLint>(offset_), source.width, static_cast<GLsizei>(rows), GL_RGBA,
                            GL_UNSIGNED_BYTE, source.rgba.data() + offset_ * row_bytes);
      spent += rows * row_bytes;
      offset_ += rows;
      if (offset_ >= static_cast<size_t>(source.height)) {
        const int levels = mip_levels(source);
        if (levels > 1) gl::api.GenerateMipmap(GL_TEXTURE_2D);
        gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_LINEAR_MIPMAP_LINEAR : GL_LINEAR);
        gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER,
                              source.mag == scene::Filter::nearest ? GL_NEAREST : GL_LINEAR);
        gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, source.repeat_s ? GL_REPEAT : GL_CLAMP_TO_EDGE);
        gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, source.repeat_t ? GL_REPEAT : GL_CLAMP_TO_EDGE);
        gl::api.BindTexture(GL_TEXTURE_2D, 0);
        ++texture_cursor_;
        offset_ = 0;
      }
    } else {
      bytes_ += spent;
      finish();
      return true;
    }
  }
  bytes_ += spent;
  return false;
}

void SceneGpu::finish() {
  const scene::Scene& scene = *source_;
  for (const scene::Instance& instance : scene.instances)
    draws_.push_back({instance.mesh, scene.meshes[static_cast<size_t>(instance.mesh)].material, instance.world});
  // Untextured, textured, then alpha-tested: one program switch per group, and the tested ones,
  // which lose early depth rejection, drawn last over the depth the others have laid.
  auto group = [&](const Draw& draw) {
    const scene::Material& material = materials_[static_cast<size_t>(draw.material)];
    return material.alpha_tested() ? 2 : material.base_color_texture >= 0 ? 1 : 0;
  };
  std::stable_sort(draws_.begin(), draws_.end(), [&](const Draw& a, const Draw& b) { return group(a) < group(b); });
  bounds_ = scene.bounds;
  radius_ = scene.bounds.radius();
  centre_ = scene.bounds.centre();
  gl::api.BindBuffer(GL_COPY_WRITE_BUFFER, 0);
  const GLenum status = gl::api.GetError();
  if (status != GL_NO_ERROR) error_ = "uploading the scene raised GL error 0x" + std::to_string(status);
  ready_ = error_.empty();
  source_.reset();
}

bool SceneGpu::upload(const scene::Scene& scene, const gl::Caps& caps, std::string& error) {
  // The caller keeps the scene alive for the whole call, so it is borrowed, not copied.
  begin(std::shared_ptr<const scene::Scene>(&scene, [](const scene::Scene*) {}), caps);
  while (!step(SIZE_MAX / 2)) {
  }
  if (failed()) {
    error = error_;
    return false;
  }
  return true;
}

}  // namespace render
