#pragma once
// Scenes the player builds itself: the demo, and simple shapes whose AO is known for tests.
#include "scene/scene.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace scene {

// "builtin:NAME" for NAME in builtin_names(); nullopt for any other name.
std::optional<Scene> make_builtin(std::string_view name);
std::vector<std::string> builtin_names();

// Building blocks, also used by tests.
Mesh make_box(glm::vec3 min, glm::vec3 max, int material);
Mesh make_quad(glm::vec3 corner, glm::vec3 edge_u, glm::vec3 edge_v, int material);
Mesh make_sphere(glm::vec3 centre, float radius, int segments, int material);
void add_instance(Scene& scene, Mesh mesh, const glm::dmat4& world = glm::dmat4(1.0));

}  // namespace scene
