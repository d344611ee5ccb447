#pragma once
// glTF materials to scene::Material: glTF 2.0's metallic-roughness factors and textures,
// KHR_materials_unlit, KHR_materials_emissive_strength, alphaMode, and how each texture reads its
// coordinates (texCoord, KHR_texture_transform), which the builder bakes into the mesh's UVs.
// Failures throw LoadError naming the field (gltf_accessors.h).
#include "gltf_document.h"
#include "scene/gltf_loader.h"
#include "scene/scene.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <utility>

namespace scene::gltf {

// How a texture reads its coordinates: the TEXCOORD set, and the KHR_texture_transform matrix
// baked into the mesh's UVs at load (exact: the transform is affine, and each converted mesh has
// exactly one material). A material's textures share at most two mappings: the base colour's
// (Vertex::uv) and one other (Mesh::uv1), which covers the common cases (one set for all, or
// occlusion on TEXCOORD_1); a third is sampled with the first, with a warning.
struct UvMapping {
  int set = 0;
  glm::dmat3 transform{1.0};
  bool transformed = false;
  bool operator==(const UvMapping& other) const {
    return set == other.set && transformed == other.transformed && transform == other.transform;
  }
};
struct MaterialMappings {
  UvMapping first, second;
  bool has_first = false, has_second = false;
};

class MaterialReader {
 public:
  // Adds glTF's default material to `scene` as its material 0.
  MaterialReader(Document& document, Scene& scene, LoadReport& report);
  // The Scene material of glTF material `index` (-1: the default), read once; `where` names the
  // primitive that refers to it.
  int material(int index, const std::string& where);
  // The UV mappings of a Scene material material() returned.
  const MaterialMappings& mappings(int scene_material) { return uv_mappings_[scene_material]; }

 private:
  static float unit_factor(double value, const std::string& field);
  static void read_texture_transform(const nlohmann::json& extension, const std::string& field, UvMapping& mapping);
  int texture(int index, const std::string& field, bool srgb);
  int white_texture();

  Document& document_;
  const tinygltf::Model& model_;
  Scene& scene_;
  LoadReport& report_;
  std::map<int, MaterialMappings> uv_mappings_;  // by Scene material index
  std::map<int, int> materials_;
  std::map<std::pair<int, bool>, int> textures_;  // (glTF texture, sRGB) -> Scene texture
  int white_ = -1;
};

}  // namespace scene::gltf
