#include "scene/procedural.h"

#include <cmath>
#include <numbers>

#include <glm/gtc/matrix_transform.hpp>

namespace scene {
namespace {

void finish(Mesh& mesh) {
  mesh.min = glm::vec3(std::numeric_limits<float>::max());
  mesh.max = glm::vec3(std::numeric_limits<float>::lowest());
  for (const Vertex& v : mesh.vertices) {
    mesh.min = glm::min(mesh.min, v.position);
    mesh.max = glm::max(mesh.max, v.position);
  }
}

// The built-in scenes are matte paint: a dielectric, rough enough that the studio's soft boxes
// show as broad sheens rather than mirror images.
Material solid(glm::vec3 colour) {
  Material material;
  material.base_color = glm::vec4(colour, 1.0f);
  material.metallic = 0.0f;
  material.roughness = 0.6f;
  return material;
}

}  // namespace

Mesh make_quad(glm::vec3 corner, glm::vec3 edge_u, glm::vec3 edge_v, int material) {
  Mesh mesh;
  const glm::vec3 normal = glm::normalize(glm::cross(edge_u, edge_v));
  mesh.vertices = {{corner, normal, {0, 0}},
                   {corner + edge_u, normal, {1, 0}},
                   {corner + edge_u + edge_v, normal, {1, 1}},
                   {corner + edge_v, normal, {0, 1}}};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  mesh.material = material;
  finish(mesh);
  return mesh;
}

Mesh make_box(glm::vec3 lo, glm::vec3 hi, int material) {
  Mesh mesh;
  mesh.material = material;
  const glm::vec3 size = hi - lo;
  const glm::vec3 x(size.x, 0, 0), y(0, size.y, 0), z(0, 0, size.z);
  // Six faces, each wound counter-clockwise seen from outside.
  const Mesh faces[] = {make_quad(lo, y, x, material),     make_quad(lo + z, x, y, material), make_quad(lo, z, y, material),
                        make_quad(lo + x, y, z, material), make_quad(lo, x, z, material),     make_quad(lo + y, z, x, material)};
  for (const Mesh& face : faces) {
    const auto base = static_cast<uint32_t>(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), face.vertices.begin(), face.vertices.end());
    for (uint32_t index : face.indices) mesh.indices.push_back(base + index);
  }
  finish(mesh);
  return mesh;
}

Mesh make_sphere(glm::vec3 centre, float radius, int segments, int material) {
  Mesh mesh;
  mesh.material = material;
  const int rings = segments / 2;
  for (int r = 0; r <= rings; ++r) {
    const double theta = std::numbers::pi * r / rings;
    for (int s = 0; s <= segments; ++s) {
      const double phi = 2.0 * std::numbers::pi * s / segments;
      const glm::vec3 n(static_cast<float>(std::sin(theta) * std::cos(phi)), static_cast<float>(std::cos(theta)),
                        static_cast<float>(-std::sin(theta) * std::sin(phi)));
      mesh.vertices.push_back({centre + radius * n, n, {static_cast<float>(s) / segments, static_cast<float>(r) / rings}});
    }
  }
  const auto stride = static_cast<uint32_t>(segments + 1);
  for (uint32_t r = 0; r < static_cast<uint32_t>(rings); ++r)
    for (uint32_t s = 0; s < static_cast<uint32_t>(segments); ++s) {
      const uint32_t a = r * stride + s, b = a + stride;
      mesh.indices.insert(mesh.indices.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
  finish(mesh);
  return mesh;
}

void add_instance(Scene& scene, Mesh mesh, const glm::dmat4& world) {
  scene.meshes.push_back(std::move(mesh));
  scene.instances.push_back({static_cast<int>(scene.meshes.size()) - 1, world});
}

std::vector<std::string> builtin_names() {
  return {"demo", "plane", "corner", "spheres"};
}

std::optional<Scene> make_builtin(std::string_view name) {
  Scene scene;
  scene.name = "builtin:" + std::string(name);
  if (name == "demo") {
    // A floor, a staircase against a wall, an arch of boxes and spheres on the floor: inside corners,
    // contact shadows and open faces side by side.
    scene.materials = {solid({0.80f, 0.78f, 0.74f}), solid({0.85f, 0.35f, 0.25f}), solid({0.25f, 0.50f, 0.85f}),
                       solid({0.90f, 0.80f, 0.30f})};
    add_instance(scene, make_box({-4, -0.2f, -4}, {4, 0, 4}, 0));
    add_instance(scene, make_box({-4, 0, -4}, {4, 2.5f, -3.6f}, 0));
    for (int step = 0; step < 5; ++step)
      add_instance(scene, make_box({-3.5f + step * 0.5f, 0, -3.6f}, {-3.0f + step * 0.5f, 0.4f * (5 - step), -2.4f}, 1));
    add_instance(scene, make_box({0.5f, 0, -1.5f}, {1.0f, 1.5f, -0.5f}, 2));
    add_instance(scene, make_box({2.5f, 0, -1.5f}, {3.0f, 1.5f, -0.5f}, 2));
    add_instance(scene, make_box({0.5f, 1.5f, -1.5f}, {3.0f, 2.0f, -0.5f}, 2));
    add_instance(scene, make_sphere({-1.0f, 0.8f, 1.2f}, 0.8f, 48, 3));
    add_instance(scene, make_sphere({0.3f, 0.45f, 1.8f}, 0.45f, 32, 3));
    add_instance(scene, make_sphere({1.8f, 0.6f, 1.0f}, 0.6f, 40, 1));
  } else if (name == "plane") {
    // A 2 x 2 square in the z = 0 plane facing +Z: seen head-on with --azimuth 0 --elevation 0.
    scene.materials = {solid({0.8f, 0.8f, 0.8f})};
    add_instance(scene, make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0));
  } else if (name == "corner") {
    // Floor y = 0 with walls x = 0 and z = 0: the inside corner of a room, open towards +X, +Y, +Z.
    scene.materials = {solid({0.8f, 0.8f, 0.8f})};
    add_instance(scene, make_quad({0, 0, 0}, {0, 0, 2}, {2, 0, 0}, 0));
    add_instance(scene, make_quad({0, 0, 0}, {2, 0, 0}, {0, 2, 0}, 0));
    add_instance(scene, make_quad({0, 0, 0}, {0, 2, 0}, {0, 0, 2}, 0));
  } else if (name == "spheres") {
    // Instances of one sphere mesh on a floor: contact occlusion between curved surfaces.
    scene.materials = {solid({0.7f, 0.7f, 0.75f}), solid({0.3f, 0.6f, 0.4f})};
    add_instance(scene, make_box({-3, -0.1f, -3}, {3, 0, 3}, 0));
    scene.meshes.push_back(make_sphere({0, 0, 0}, 0.5f, 32, 1));
    const int sphere = static_cast<int>(scene.meshes.size()) - 1;
    for (int i = 0; i < 9; ++i) {
      const glm::dvec3 at(-1.2 + 1.05 * (i % 3), 0.5, -1.2 + 1.05 * (i / 3));
      scene.instances.push_back({sphere, glm::translate(glm::dmat4(1.0), at)});
    }
  } else {
    return std::nullopt;
  }
  update_bounds(scene);
  return scene;
}

}  // namespace scene
