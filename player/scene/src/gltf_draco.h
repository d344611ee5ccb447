#pragma once
// KHR_draco_mesh_compression: a primitive whose attributes and indices are one Draco-compressed
// buffer view, decoded with Debian's libdraco on the loader thread. What the extension maps is
// checked against the primitive: every named attribute exists in the decoded mesh with the
// components its accessor declares, and the counts agree with the accessors.
#include "gltf_document.h"

#include <glm/glm.hpp>

#include <map>
#include <string>
#include <vector>

namespace scene::gltf {

struct DracoPrimitive {
  size_t points = 0;
  std::vector<uint32_t> indices;                         // a triangle list
  std::map<std::string, std::vector<float>> attributes;  // glTF attribute name -> points x components
  std::map<std::string, int> components;
};

// Decodes the primitive `primitive_json` (its "extensions" hold the Draco object) whose glTF
// attributes are `attributes` (name -> accessor); throws LoadError naming `where`.
DracoPrimitive decode_draco(Document& document, const nlohmann::json& extension, const std::map<std::string, int>& attributes,
                            int indices_accessor, const std::string& where);

}  // namespace scene::gltf
