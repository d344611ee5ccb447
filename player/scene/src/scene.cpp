#include "scene/scene.h"

#include <limits>

namespace scene {

size_t Scene::triangle_count() const {
  size_t count = 0;
  for (const Instance& instance : instances) count += meshes[static_cast<size_t>(instance.mesh)].indices.size() / 3;
  return count;
}

void update_bounds(Scene& scene) {
  Bounds bounds{glm::dvec3(std::numeric_limits<double>::max()), glm::dvec3(std::numeric_limits<double>::lowest())};
  for (const Instance& instance : scene.instances) {
    const Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    for (int corner = 0; corner < 8; ++corner) {
      const glm::dvec3 local((corner & 1) ? mesh.max.x : mesh.min.x, (corner & 2) ? mesh.max.y : mesh.min.y,
                             (corner & 4) ? mesh.max.z : mesh.min.z);
      const glm::dvec3 world(instance.world * glm::dvec4(local, 1.0));
      bounds.min = glm::min(bounds.min, world);
      bounds.max = glm::max(bounds.max, world);
    }
  }
  if (scene.instances.empty()) bounds = Bounds{};
  scene.bounds = bounds;
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
    instance.world = instance.world * glm::dmat4(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, c.x, c.y, c.z, 1);
  }
  update_bounds(scene);
}

}  // namespace scene
