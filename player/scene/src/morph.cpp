#include "scene/scene.h"

#include <cmath>

namespace scene {

void morph_vertices(const Mesh& mesh, const float* weights, std::vector<Vertex>& out) {
  const Mesh::Morph& morph = mesh.morph;
  const size_t count = mesh.vertices.size();
  for (size_t i = 0; i < count; ++i) out[i] = mesh.vertices[i];
  for (size_t t = 0; t < morph.target_count(); ++t) {
    // From the shape the mesh holds, so only the change of each weight moves a position.
    const float change = weights[t] - morph.weights[t];
    const std::vector<glm::vec3>& moved = morph.positions[t];
    if (change != 0.0f && !moved.empty())
      for (size_t i = 0; i < count; ++i) out[i].position += change * moved[i];
  }
  if (!morph.base_normals.empty()) {
    for (size_t i = 0; i < count; ++i) {
      glm::vec3 normal = morph.base_normals[i];
      for (size_t t = 0; t < morph.target_count(); ++t)
        if (!morph.normals[t].empty()) normal += weights[t] * morph.normals[t][i];
      const float length = glm::length(normal);
      out[i].normal = length > 1e-30f && std::isfinite(length) ? normal / length : glm::vec3(0.0f);
    }
    return;
  }
  // Flat normals: the loader gave each triangle its own three vertices, in order.
  for (size_t v = 0; v + 2 < count; v += 3) {
    const glm::vec3 a = out[v].position, b = out[v + 1].position, c = out[v + 2].position;
    const glm::vec3 cross = glm::cross(b - a, c - a);
    const float length = glm::length(cross);
    const glm::vec3 normal = length > 0.0f && std::isfinite(length) ? cross / length : glm::vec3(0.0f);
    out[v].normal = out[v + 1].normal = out[v + 2].normal = normal;
  }
}

void skin_vertices(const Mesh& mesh, const std::vector<glm::dmat4>& matrices, std::vector<Vertex>& out) {
  for (size_t i = 0; i < mesh.vertices.size(); ++i) {
    glm::dmat4 blend(0.0);
    for (int k = 0; k < 4; ++k)
      if (mesh.joint_weights[i][k] != 0.0f) blend += double(mesh.joint_weights[i][k]) * matrices[mesh.joints[i][k]];
    out[i] = mesh.vertices[i];
    out[i].position = glm::vec3(blend * glm::dvec4(mesh.vertices[i].position, 1.0));
    const glm::dvec3 normal = glm::dmat3(blend) * glm::dvec3(mesh.vertices[i].normal);
    const double length = glm::length(normal);
    out[i].normal = length > 1e-30 ? glm::vec3(normal / length) : glm::vec3(0.0f);
  }
}

}  // namespace scene
