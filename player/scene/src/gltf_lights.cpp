#include "gltf_lights.h"

#include "gltf_accessors.h"

#include <cmath>

namespace scene::gltf {
namespace {

constexpr double kHalfPi = 1.5707963267948966;

double number(const nlohmann::json& object, const char* key, double fallback, const std::string& where) {
  const auto found = object.find(key);
  if (found == object.end()) return fallback;
  if (!found->is_number() || !std::isfinite(found->get<double>())) fail(where + "." + key + ": expected a finite number");
  return found->get<double>();
}

Light definition(const nlohmann::json& source, const std::string& where) {
  Light light;
  const std::string& type = source.at("type").get_ref<const std::string&>();
  light.type = type == "directional" ? Light::Type::directional : type == "point" ? Light::Type::point : Light::Type::spot;
  glm::dvec3 color(1.0);
  if (const auto found = source.find("color"); found != source.end()) {
    if (!found->is_array() || found->size() != 3) fail(where + ".color: expected 3 numbers");
    for (int c = 0; c < 3; ++c) {
      const nlohmann::json& value = (*found)[static_cast<size_t>(c)];
      if (!value.is_number() || !(value.get<double>() >= 0.0 && value.get<double>() <= 1.0))
        fail(where + ".color[" + std::to_string(c) + "]: expected a number in [0, 1]");
      color[c] = value.get<double>();
    }
  }
  const double intensity = number(source, "intensity", 1.0, where);
  if (intensity < 0.0) fail(where + ".intensity: " + std::to_string(intensity) + "; expected a number >= 0");
  // Linear RGB times intensity must stay a float: a file's 1e300 candela would shade as infinity.
  if (intensity > 1e30) fail(where + ".intensity: " + std::to_string(intensity) + "; expected at most 1e30");
  light.color = glm::vec3(color * intensity);
  // A directional light has no range (the validator warns of one and it is ignored, as glTF says).
  if (light.type != Light::Type::directional) {
    light.range = number(source, "range", 0.0, where);
    if (source.contains("range") && !(light.range > 0.0))
      fail(where + ".range: " + std::to_string(light.range) + "; expected a number > 0");
  }
  if (light.type == Light::Type::spot) {
    const auto spot = source.find("spot");
    if (spot == source.end() || !spot->is_object()) fail(where + ".spot: a spot light requires its cone (spot)");
    light.inner_cone = number(*spot, "innerConeAngle", 0.0, where + ".spot");
    light.outer_cone = number(*spot, "outerConeAngle", kHalfPi / 2.0, where + ".spot");
    if (!(light.inner_cone >= 0.0 && light.inner_cone < light.outer_cone && light.outer_cone <= kHalfPi))
      fail(where + ".spot: innerConeAngle " + std::to_string(light.inner_cone) + " and outerConeAngle " +
           std::to_string(light.outer_cone) + "; expected 0 <= innerConeAngle < outerConeAngle <= pi/2");
  }
  return light;
}

}  // namespace

LightReader::LightReader(const nlohmann::json& root, std::vector<std::string>& warnings) : warnings_(warnings) {
  const auto extensions = root.find("extensions");
  if (extensions == root.end() || !extensions->is_object()) return;
  const auto extension = extensions->find("KHR_lights_punctual");
  if (extension == extensions->end()) return;
  const std::string where = "extensions.KHR_lights_punctual";
  if (!extension->is_object()) fail(where + ": expected an object");
  has_extension_ = true;
  const auto lights = extension->find("lights");
  if (lights == extension->end()) fail(where + ".lights: required");
  if (!lights->is_array() || lights->empty()) fail(where + ".lights: expected a non-empty array");
  for (size_t i = 0; i < lights->size(); ++i) {
    const std::string field = where + ".lights[" + std::to_string(i) + "]";
    const nlohmann::json& source = (*lights)[i];
    if (!source.is_object()) fail(field + ": expected an object");
    const auto type = source.find("type");
    if (type == source.end() || !type->is_string()) fail(field + ".type: expected \"directional\", \"point\" or \"spot\"");
    const std::string& name = type->get_ref<const std::string&>();
    if (name != "directional" && name != "point" && name != "spot") {
      warnings.push_back(field + ".type: \"" + name + "\" is not a light type this player knows; the light is left out");
      definitions_.emplace_back();
      continue;
    }
    definitions_.push_back(definition(source, field));
  }
}

std::optional<Light> LightReader::place(const nlohmann::json& node, int node_index, const glm::dmat4& world) const {
  const auto extensions = node.find("extensions");
  if (extensions == node.end() || !extensions->is_object()) return std::nullopt;
  const auto extension = extensions->find("KHR_lights_punctual");
  if (extension == extensions->end()) return std::nullopt;
  const std::string where = "nodes[" + std::to_string(node_index) + "].extensions.KHR_lights_punctual";
  if (!extension->is_object()) fail(where + ": expected an object");
  const auto index = extension->find("light");
  if (index == extension->end() || !index->is_number_integer()) fail(where + ".light: expected a light index");
  if (!has_extension_) fail(where + ".light: the file defines no lights (extensions.KHR_lights_punctual.lights at its root)");
  const auto at = index->get<long long>();
  if (at < 0 || static_cast<size_t>(at) >= definitions_.size())
    fail(where + ".light: " + std::to_string(at) + " out of range (there are " + std::to_string(definitions_.size()) + ")");
  const std::optional<Light>& defined = definitions_[static_cast<size_t>(at)];
  if (!defined) return std::nullopt;
  Light light = *defined;
  light.node = node_index;
  // A node scaled to nothing (how animations often hide a part) has no direction: its light is
  // left out, as a camera's node is, rather than the file refused.
  if (!place_light(light, world)) {
    warnings_.push_back("nodes[" + std::to_string(node_index) +
                        "]: the transform leaves its light no direction or position; the light is left out");
    return std::nullopt;
  }
  return light;
}

}  // namespace scene::gltf
