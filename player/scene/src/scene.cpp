#include "scene/scene.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scene {

size_t Scene::triangle_count() const {
  size_t count = 0;
  for (const Instance& instance : instances) count += meshes[static_cast<size_t>(instance.mesh)].indices.size() / 3;
  return count;
}

namespace {

// Widens `bounds` by the box [min, max] moved by `transform`.
void add_box(Bounds& bounds, const glm::dmat4& transform, const glm::vec3& min, const glm::vec3& max) {
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 local((corner & 1) ? max.x : min.x, (corner & 2) ? max.y : min.y, (corner & 4) ? max.z : min.z);
    const glm::dvec3 world(transform * glm::dvec4(local, 1.0));
    bounds.min = glm::min(bounds.min, world);
    bounds.max = glm::max(bounds.max, world);
  }
}

// A skinned vertex is a weighted mean of its joints' transforms of it, so it lies within the
// boxes of those transforms; each joint's box holds only the vertices it moves.
void add_skinned(Bounds& bounds, const Mesh& mesh, const Instance& instance) {
  const size_t joints = instance.skin_matrices.size();
  std::vector<glm::vec3> low(joints, glm::vec3(std::numeric_limits<float>::max())),
      high(joints, glm::vec3(std::numeric_limits<float>::lowest()));
  for (size_t i = 0; i < mesh.vertices.size(); ++i)
    for (int k = 0; k < 4; ++k) {
      const size_t joint = mesh.joints[i][k];
      if (mesh.joint_weights[i][k] <= 0.0f || joint >= joints) continue;
      low[joint] = glm::min(low[joint], mesh.vertices[i].position);
      high[joint] = glm::max(high[joint], mesh.vertices[i].position);
    }
  for (size_t joint = 0; joint < joints; ++joint)
    if (low[joint].x <= high[joint].x) add_box(bounds, instance.skin_matrices[joint] * instance.offset, low[joint], high[joint]);
}

}  // namespace

void update_bounds(Scene& scene) {
  Bounds bounds{glm::dvec3(std::numeric_limits<double>::max()), glm::dvec3(std::numeric_limits<double>::lowest())};
  for (const Instance& instance : scene.instances) {
    const Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    if (instance.skin >= 0 && !mesh.joints.empty())
      add_skinned(bounds, mesh, instance);
    else
      add_box(bounds, instance.world, mesh.min, mesh.max);
  }
  if (scene.instances.empty()) bounds = Bounds{};
  scene.bounds = bounds;
}

bool place_light(Light& light, const glm::dmat4& world) {
  const glm::dvec3 position(world[3]);
  const glm::dvec3 axis(world * glm::dvec4(0.0, 0.0, -1.0, 0.0));
  const double length = glm::length(axis);
  const bool aimed = std::isfinite(length) && length > 1e-12;
  if (!std::isfinite(position.x + position.y + position.z) || (!aimed && light.type != Light::Type::point)) return false;
  light.position = position;
  if (aimed) light.direction = axis / length;
  return true;
}

void place_camera(FileCamera& camera, const glm::dmat4& world) {
  camera.world = world;
  camera.unplaced = {};
  const glm::dvec3 eye(world[3]), forward(world * glm::dvec4(0, 0, -1, 0)), up(world * glm::dvec4(0, 1, 0, 0));
  const auto finite = [](const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
  if (!finite(eye) || !finite(forward) || !finite(up))
    camera.unplaced = "its node's transform is not finite";
  else if (glm::length(forward) < 1e-12 || glm::length(up) < 1e-12 ||
           glm::length(glm::cross(glm::normalize(forward), glm::normalize(up))) < 1e-6)
    camera.unplaced = "its node's transform scales its view direction or its up to nothing";
}

void recenter_meshes(Scene& scene) {
  std::vector<glm::dvec3> offsets;
  for (Mesh& mesh : scene.meshes) {
    const glm::dvec3 centre = (glm::dvec3(mesh.min) + glm::dvec3(mesh.max)) * 0.5;
    for (Vertex& v : mesh.vertices) v.position = glm::vec3(glm::dvec3(v.position) - centre);
    mesh.min = glm::vec3(glm::dvec3(mesh.min) - centre);
    mesh.max = glm::vec3(glm::dvec3(mesh.max) - centre);
    offsets.push_back(centre);
  }
  for (Instance& instance : scene.instances) {
    const glm::dvec3& c = offsets[static_cast<size_t>(instance.mesh)];
    const glm::dmat4 moved(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, c.x, c.y, c.z, 1);
    instance.world = instance.world * moved;
    instance.offset = instance.offset * moved;
  }
  update_bounds(scene);
}

void generate_tangents(Mesh& mesh, bool from_uv1) {
  const size_t count = mesh.vertices.size();
  std::vector<glm::dvec3> tangent(count, glm::dvec3(0.0)), bitangent(count, glm::dvec3(0.0));
  auto uv = [&](uint32_t i) { return glm::dvec2(from_uv1 ? mesh.uv1[i] : mesh.vertices[i].uv); };
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const uint32_t corner[3] = {mesh.indices[t], mesh.indices[t + 1], mesh.indices[t + 2]};
    for (int k = 0; k < 3; ++k) {
      // Each corner's own edges, weighted by the corner's angle as MikkTSpace weights them, so a
      // vertex's frame does not depend on how finely the faces around it are split.
      const uint32_t i = corner[k], j = corner[(k + 1) % 3], l = corner[(k + 2) % 3];
      const glm::dvec3 p = mesh.vertices[i].position;
      const glm::dvec3 e1 = glm::dvec3(mesh.vertices[j].position) - p, e2 = glm::dvec3(mesh.vertices[l].position) - p;
      const glm::dvec2 d1 = uv(j) - uv(i), d2 = uv(l) - uv(i);
      const double det = d1.x * d2.y - d2.x * d1.y;
      const double lengths = glm::length(e1) * glm::length(e2);
      if (std::abs(det) < 1e-20 || lengths <= 0.0 || !std::isfinite(det)) continue;  // no UV area: says nothing
      const double angle = std::acos(std::clamp(glm::dot(e1, e2) / lengths, -1.0, 1.0));
      const glm::dvec3 s = (e1 * d2.y - e2 * d1.y) / det, b = (e2 * d1.x - e1 * d2.x) / det;
      const double s_length = glm::length(s), b_length = glm::length(b);
      if (s_length > 0.0 && std::isfinite(s_length)) tangent[i] += s / s_length * angle;
      if (b_length > 0.0 && std::isfinite(b_length)) bitangent[i] += b / b_length * angle;
    }
  }
  mesh.tangents.assign(count, glm::vec4(1, 0, 0, 1));
  for (size_t i = 0; i < count; ++i) {
    const glm::dvec3 n = mesh.vertices[i].normal;
    glm::dvec3 t = tangent[i] - n * glm::dot(n, tangent[i]);  // Gram-Schmidt onto the normal's plane
    double length = glm::length(t);
    if (!(length > 1e-12)) {
      // No UV gradient here (a degenerate mapping): any vector in the plane keeps the frame valid.
      t = std::abs(n.x) < 0.9 ? glm::cross(n, glm::dvec3(1, 0, 0)) : glm::cross(n, glm::dvec3(0, 1, 0));
      length = glm::length(t);
      if (!(length > 1e-12)) continue;  // a zero normal: the shader faces it to the eye anyway
    }
    t /= length;
    // glTF's v runs down the image while a normal map's +Y points up it: the bitangent the shader
    // rebuilds as w * cross(n, t) must follow -dP/dv, as the Khronos sample viewer's does.
    const double handedness = glm::dot(glm::cross(n, t), bitangent[i]) > 0.0 ? -1.0 : 1.0;
    mesh.tangents[i] = glm::vec4(glm::vec3(t), static_cast<float>(handedness));
  }
}

}  // namespace scene
