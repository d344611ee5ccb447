#include "render/scene_gpu.h"

#include "render/programs.h"
#include "render/uniform_blocks.h"

#include "gl_util.h"
#include "scene/environment.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace render {
namespace {

// The smallest slice worth a call: below this the per-call overhead dominates.
constexpr size_t kMinSlice = 64 * 1024;

// A mesh's bytes go up as consecutive ranges: vertices, tangents, second UVs, joints, joint
// weights, indices.
struct Ranges {
  size_t vertices, tangents, uv1, joints, joint_weights, indices;
  size_t total() const { return vertices + tangents + uv1 + joints + joint_weights + indices; }
};
Ranges ranges_of(const scene::Mesh& mesh) {
  return {mesh.vertices.size() * sizeof(scene::Vertex),  mesh.tangents.size() * sizeof(glm::vec4),
          mesh.uv1.size() * sizeof(glm::vec2),           mesh.joints.size() * sizeof(mesh.joints[0]),
          mesh.joint_weights.size() * sizeof(glm::vec4), mesh.indices.size() * sizeof(uint32_t)};
}

// The skinned draws' joints, 64 to a row of the texture (three texels each).
constexpr int kJointsPerRow = 64;

gl::Buffer stream(GLuint location, GLint components, size_t bytes) {
  gl::Buffer buffer = gl::make_buffer();
  gl::api.BindBuffer(GL_ARRAY_BUFFER, buffer.id());
  gl::api.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(bytes), nullptr, GL_STATIC_DRAW);
  gl::api.EnableVertexAttribArray(location);
  gl::api.VertexAttribPointer(location, components, GL_FLOAT, GL_FALSE, 0, nullptr);
  return buffer;
}

SceneGpu::Mesh allocate_mesh(const scene::Mesh& mesh) {
  SceneGpu::Mesh gpu;
  gpu.vao = gl::make_vertex_array();
  gl::api.BindVertexArray(gpu.vao.id());
  const Ranges bytes = ranges_of(mesh);
  // Attribute 3 (tangents) and 4 (second UVs) only where the mesh has them; the variants that
  // read them are only used for materials that make the loader provide them.
  if (bytes.tangents) gpu.tangents = stream(3, 4, bytes.tangents);
  if (bytes.uv1) gpu.uv1 = stream(4, 2, bytes.uv1);
  // Attributes 5 (joints, integers) and 6 (their weights) only for a skinned mesh.
  if (bytes.joints) {
    gpu.joints = gl::make_buffer();
    gl::api.BindBuffer(GL_ARRAY_BUFFER, gpu.joints.id());
    gl::api.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(bytes.joints), nullptr, GL_STATIC_DRAW);
    gl::api.EnableVertexAttribArray(5);
    gl::api.VertexAttribIPointer(5, 4, GL_UNSIGNED_SHORT, 0, nullptr);
    gpu.joint_weights = stream(6, 4, bytes.joint_weights);
  }
  gpu.vertices = gl::make_buffer();
  gl::api.BindBuffer(GL_ARRAY_BUFFER, gpu.vertices.id());
  // A morphed mesh's vertices are sent again whenever its weights change.
  gl::api.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(bytes.vertices), nullptr,
                     mesh.morph.target_count() ? GL_DYNAMIC_DRAW : GL_STATIC_DRAW);
  gpu.indices = gl::make_buffer();
  gl::api.BindBuffer(GL_ELEMENT_ARRAY_BUFFER, gpu.indices.id());
  gl::api.BufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(bytes.indices), nullptr, GL_STATIC_DRAW);
  constexpr auto stride = static_cast<GLsizei>(sizeof(scene::Vertex));
  gl::api.EnableVertexAttribArray(0);
  gl::api.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(scene::Vertex, position)));
  gl::api.EnableVertexAttribArray(1);
  gl::api.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(scene::Vertex, normal)));
  gl::api.EnableVertexAttribArray(2);
  gl::api.VertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(scene::Vertex, uv)));
  // Attribute 7, the previous pose's positions: a morphed mesh's own buffer (finish() fills it),
  // everyone else's unmoved positions.
  if (mesh.morph.target_count()) {
    gpu.previous_positions = gl::make_buffer();
    gl::api.BindBuffer(GL_ARRAY_BUFFER, gpu.previous_positions.id());
    gl::api.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(mesh.vertices.size() * sizeof(glm::vec3)), nullptr,
                       GL_DYNAMIC_DRAW);
    gl::api.EnableVertexAttribArray(7);
    gl::api.VertexAttribPointer(7, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  } else {
    gl::api.EnableVertexAttribArray(7);
    gl::api.VertexAttribPointer(7, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(offsetof(scene::Vertex, position)));
  }
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
  blended_.clear();
  morphed_.clear();
  joint_rows_.clear();
  joint_matrices_ = gl::Texture();
  rig_.reset();
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
      const Ranges bytes = ranges_of(mesh);
      const size_t total = bytes.total();
      const size_t end = std::min(total, offset_ + slice);
      // Each range takes the part of [offset_, end) that falls within it.
      size_t start = 0;
      auto part = [&](const gl::Buffer& buffer, const void* data, size_t size) {
        const size_t from = std::clamp(offset_, start, start + size) - start, to = std::clamp(end, start, start + size) - start;
        upload_range(buffer, data, from, to);
        start += size;
      };
      part(gpu.vertices, mesh.vertices.data(), bytes.vertices);
      part(gpu.tangents, mesh.tangents.data(), bytes.tangents);
      part(gpu.uv1, mesh.uv1.data(), bytes.uv1);
      part(gpu.joints, mesh.joints.data(), bytes.joints);
      part(gpu.joint_weights, mesh.joint_weights.data(), bytes.joint_weights);
      part(gpu.indices, mesh.indices.data(), bytes.indices);
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
        gl::api.TexStorage2D(GL_TEXTURE_2D, mip_levels(source), source.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, source.width,
                             source.height);
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

void SceneGpu::upload_environment() {
  std::shared_ptr<const scene::Environment> wanted = source_->environment;
  // The studio lives for the whole process; it is shared, not owned.
  if (!wanted) wanted = std::shared_ptr<const scene::Environment>(&scene::studio_environment(), [](const scene::Environment*) {});
  if (environment_.source == wanted.get() && environment_.specular) return;
  const scene::Environment& source = *wanted;
  EnvironmentGpu gpu;
  gpu.levels = source.levels();
  gpu.specular = gl::make_texture();
  gl::api.BindTexture(GL_TEXTURE_CUBE_MAP, gpu.specular.id());
  gl::api.TexStorage2D(GL_TEXTURE_CUBE_MAP, gpu.levels, GL_RGBA16F, source.face_size, source.face_size);
  gl::api.PixelStorei(GL_UNPACK_ALIGNMENT, 4);
  std::vector<float> rgba;
  for (int level = 0; level < gpu.levels; ++level) {
    const int size = std::max(source.face_size >> level, 1);
    const std::vector<float>& faces = source.specular[static_cast<size_t>(level)];
    const size_t texels = static_cast<size_t>(size) * static_cast<size_t>(size);
    for (int face = 0; face < 6; ++face) {
      // RGB float rows are not 4-byte aligned for every size in every driver's eyes; RGBA is.
      rgba.resize(texels * 4);
      for (size_t t = 0; t < texels; ++t)
        for (size_t c = 0; c < 4; ++c) rgba[t * 4 + c] = c < 3 ? faces[(static_cast<size_t>(face) * texels + t) * 3 + c] : 1.0f;
      gl::api.TexSubImage2D(GL_TEXTURE_CUBE_MAP_POSITIVE_X + static_cast<GLenum>(face), level, 0, 0, size, size, GL_RGBA,
                            GL_FLOAT, rgba.data());
    }
  }
  gl::api.TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  gl::api.TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl::api.TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl::api.TexParameteri(GL_TEXTURE_CUBE_MAP, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl::api.BindTexture(GL_TEXTURE_CUBE_MAP, 0);
  for (size_t i = 0; i < gpu.irradiance.size(); ++i) gpu.irradiance[i] = glm::vec4(source.irradiance_sh[i], 0.0f);
  gpu.source = wanted.get();
  environment_ = std::move(gpu);
  environment_source_ = std::move(wanted);
}

void SceneGpu::finish() {
  upload_environment();
  const scene::Scene& scene = *source_;
  const shared_layout::LightParams lights = pack_light_params(scene.lights);
  lights_ = detail::make_uniform_buffer(&lights, sizeof lights);
  light_count_ = lights.count;
  for (const scene::Instance& instance : scene.instances) {
    const scene::Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    const glm::dvec3 box_centre = glm::dvec3(mesh.min + mesh.max) * 0.5;
    const bool blended = materials_[static_cast<size_t>(mesh.material)].alpha_mode == scene::AlphaMode::blend;
    const bool skinned = instance.skin >= 0 && !mesh.joints.empty();
    (blended ? blended_ : draws_)
        .push_back({instance.mesh, mesh.material, instance.world, box_centre, instance.node, instance.offset,
                    skinned ? instance.skin : -1, static_cast<int>(joint_rows_.size() / 3), instance.world});
    if (!skinned) continue;
    Draw& draw = (blended ? blended_ : draws_).back();
    // Whole rows of three texels per joint; the draw's joints start where the last draw's end.
    joint_rows_.resize(joint_rows_.size() + instance.skin_matrices.size() * 3);
    write_joints(draw, instance.skin_matrices);
    pose_joints_.reserve(std::max(pose_joints_.capacity(), instance.skin_matrices.size()));
  }
  if (!joint_rows_.empty()) {
    const size_t joints = joint_rows_.size() / 3;
    const size_t rows = (joints + kJointsPerRow - 1) / kJointsPerRow;
    joint_rows_.resize(rows * kJointsPerRow * 3, glm::vec4(0.0f));
    // The previous pose's half, the same until a pose moves something.
    joint_rows_.insert(joint_rows_.end(), joint_rows_.begin(), joint_rows_.end());
    joint_matrices_ = gl::make_texture();
    gl::api.BindTexture(GL_TEXTURE_2D, joint_matrices_.id());
    gl::api.TexStorage2D(GL_TEXTURE_2D, 1, GL_RGBA32F, kJointsPerRow * 3, static_cast<GLsizei>(2 * rows));
    gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    upload_joints();
  }
  rig_ = scene.rig;
  const bool lights_move =
      std::any_of(scene.lights.begin(), scene.lights.end(), [](const scene::Light& light) { return light.rig_node >= 0; });
  placed_lights_ = lights_move ? scene.lights : std::vector<scene::Light>();
  for (const scene::Instance& instance : scene.instances) {
    const scene::Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    if (instance.node < 0 || mesh.morph.target_count() == 0) continue;
    Morphed morphed{instance.mesh, instance.node, scene::Mesh(), mesh.morph.weights, {}, false};
    morphed.source.vertices = mesh.vertices;
    morphed.source.morph = mesh.morph;
    morphed.positions.reserve(mesh.vertices.size());
    for (const scene::Vertex& vertex : mesh.vertices) morphed.positions.push_back(vertex.position);
    upload_range(meshes_[static_cast<size_t>(instance.mesh)].previous_positions, morphed.positions.data(), 0,
                 morphed.positions.size() * sizeof(glm::vec3));
    shaped_.resize(std::max(shaped_.size(), mesh.vertices.size()));
    morphed_.push_back(std::move(morphed));
  }
  blend_order_.resize(blended_.size());
  // By G-buffer variant, one program switch per group; the alpha-tested last (see draws()).
  auto group = [&](const Draw& draw) {
    const scene::Material& material = materials_[static_cast<size_t>(draw.material)];
    const unsigned skinned = draw.skin >= 0 ? features::skinned : 0;
    return material.alpha_tested() ? int(features::count | skinned) : int(material_features(material, true) | skinned);
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

bool SceneGpu::write_joints(const Draw& draw, const std::vector<glm::dmat4>& skin_matrices) {
  // Relative to the anchor, so the texture holds small numbers even far from the origin.
  const glm::dmat4 from_anchor = glm::inverse(draw.world);
  bool changed = false;
  for (size_t j = 0; j < skin_matrices.size(); ++j) {
    const glm::mat4 m(from_anchor * skin_matrices[j] * draw.offset);
    glm::vec4* rows = &joint_rows_[(static_cast<size_t>(draw.joint_base) + j) * 3];
    for (int r = 0; r < 3; ++r) {
      const glm::vec4 row(m[0][r], m[1][r], m[2][r], m[3][r]);
      changed = changed || row != rows[r];
      rows[r] = row;
    }
  }
  return changed;
}

void SceneGpu::upload_joints() {
  gl::api.BindTexture(GL_TEXTURE_2D, joint_matrices_.id());
  gl::api.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kJointsPerRow * 3, static_cast<GLsizei>(joint_rows_.size() / (kJointsPerRow * 3)),
                        GL_RGBA, GL_FLOAT, joint_rows_.data());
  gl::api.BindTexture(GL_TEXTURE_2D, 0);
}

void SceneGpu::pose(const scene::Pose& pose) {
  const std::vector<glm::dmat4>& node_worlds = pose.worlds();
  bool moved = false;
  bool bent = false;
  for (std::vector<Draw>* draws : {&draws_, &blended_})
    for (Draw& draw : *draws) draw.previous_world = draw.world;
  // The joints as the last pose left them become the previous pose's half.
  const auto current_joints_end = joint_rows_.begin() + static_cast<std::ptrdiff_t>(joint_rows_.size() / 2);
  // That is no move of this pose's, only a change of what the texture holds.
  bool joints_changed = false;
  if (!std::equal(joint_rows_.begin(), current_joints_end, current_joints_end)) {
    std::copy(joint_rows_.begin(), current_joints_end, current_joints_end);
    joints_changed = true;
  }
  for (std::vector<Draw>* draws : {&draws_, &blended_})
    for (Draw& draw : *draws) {
      if (draw.skin < 0) continue;
      const scene::Rig::Skin& skin = rig_->skins[static_cast<size_t>(draw.skin)];
      const glm::dmat4& anchor = node_worlds[static_cast<size_t>(skin.joints[0])];
      moved = moved || anchor != draw.world;
      draw.world = anchor;
      scene::skin_matrices(skin, node_worlds, pose_joints_);  // within the capacity finish() gave it
      bent = write_joints(draw, pose_joints_) || bent;
    }
  if (bent || joints_changed) upload_joints();
  moved = moved || bent;
  if (scene::pose_lights(placed_lights_, pose)) {
    const shared_layout::LightParams lights = pack_light_params(placed_lights_);
    gl::api.BindBuffer(GL_UNIFORM_BUFFER, lights_.id());
    gl::api.BufferSubData(GL_UNIFORM_BUFFER, 0, sizeof lights, &lights);
    gl::api.BindBuffer(GL_UNIFORM_BUFFER, 0);  // lights do not change the AO: not a move
  }
  for (Morphed& morphed : morphed_) {
    const std::vector<float>& weights = pose.weights()[static_cast<size_t>(morphed.node)];
    const bool reshape = weights.size() == morphed.shown.size() && weights != morphed.shown;
    const Mesh& mesh = meshes_[static_cast<size_t>(morphed.mesh)];
    // The shape the buffer holds is the previous pose's from now on.
    if (reshape || morphed.moving)
      upload_range(mesh.previous_positions, morphed.positions.data(), 0, morphed.positions.size() * sizeof(glm::vec3));
    morphed.moving = reshape;
    if (!reshape) continue;
    scene::morph_vertices(morphed.source, weights.data(), shaped_);
    std::copy(weights.begin(), weights.end(), morphed.shown.begin());
    for (size_t i = 0; i < morphed.positions.size(); ++i) morphed.positions[i] = shaped_[i].position;
    upload_range(mesh.vertices, shaped_.data(), 0, morphed.source.vertices.size() * sizeof(scene::Vertex));
    moved = true;
  }
  if (!morphed_.empty()) gl::api.BindBuffer(GL_COPY_WRITE_BUFFER, 0);
  for (std::vector<Draw>* draws : {&draws_, &blended_})
    for (Draw& draw : *draws) {
      if (draw.skin >= 0 || draw.node < 0 || static_cast<size_t>(draw.node) >= node_worlds.size()) continue;
      const glm::dmat4 world = node_worlds[static_cast<size_t>(draw.node)] * draw.offset;
      if (world == draw.world) continue;
      draw.world = world;
      moved = true;
    }
  if (moved) ++pose_version_;
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
