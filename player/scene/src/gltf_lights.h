#pragma once
// KHR_lights_punctual: the file's light definitions, and the lights its nodes place. A definition
// the extension does not allow (a spot cone outside 0 <= inner < outer <= pi/2, a negative
// intensity, a missing type) refuses the file; a light type it does not know (a later revision's)
// is left out with a warning, as the validator only warns of it. Failures throw LoadError naming
// the field (gltf_accessors.h).
#include "scene/scene.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

namespace scene::gltf {

class LightReader {
 public:
  // Reads extensions.KHR_lights_punctual.lights of the checked JSON root.
  LightReader(const nlohmann::json& root, std::vector<std::string>& warnings);

  // The light node `node_index` places, if it names one, at its world transform `world`.
  // Null as well where it names a light of an unknown type, or one its transform cannot aim (warned).
  std::optional<Light> place(const nlohmann::json& node, int node_index, const glm::dmat4& world) const;

 private:
  // Unset: a type this player does not know (warned once, at reading).
  std::vector<std::optional<Light>> definitions_;
  bool has_extension_ = false;
  std::vector<std::string>& warnings_;
};

}  // namespace scene::gltf
