#include "gltf_materials.h"

#include "gltf_accessors.h"

#include <algorithm>
#include <cmath>

namespace scene::gltf {

MaterialReader::MaterialReader(Document& document, Scene& scene, LoadReport& report)
    : document_(document), model_(document.model()), scene_(scene), report_(report) {
  scene_.materials.push_back(Material{});  // index 0: glTF's default material
}

int MaterialReader::material(int index, const std::string& where) {
  if (index < 0) return 0;
  if (static_cast<size_t>(index) >= model_.materials.size())
    fail(where + ".material: " + std::to_string(index) + " out of range (there are " + std::to_string(model_.materials.size()) +
         ")");
  if (auto found = materials_.find(index); found != materials_.end()) return found->second;
  const tinygltf::Material& source = model_.materials[static_cast<size_t>(index)];
  const std::string field = "materials[" + std::to_string(index) + "]";
  Material material;
  material.double_sided = source.doubleSided;
  material.unlit = source.extensions.count("KHR_materials_unlit") > 0;
  if (source.alphaMode == "MASK" || source.alphaMode == "BLEND") {
    material.alpha_mode = source.alphaMode == "MASK" ? AlphaMode::mask : AlphaMode::blend;
    if (!std::isfinite(source.alphaCutoff) || source.alphaCutoff < 0.0)
      fail(field + ".alphaCutoff: " + std::to_string(source.alphaCutoff) + "; expected a number of at least 0");
    material.alpha_cutoff = static_cast<float>(source.alphaCutoff);
    // glTF ignores the cutoff of a blended material; the player uses it where it cannot blend (a
    // light field module's G-buffer), at 0.5, which keeps labels and foliage legible.
    if (material.alpha_mode == AlphaMode::blend) material.alpha_cutoff = 0.5f;
  } else if (source.alphaMode != "OPAQUE") {
    fail(field + ".alphaMode: \"" + source.alphaMode + "\"; expected \"OPAQUE\", \"MASK\" or \"BLEND\"");
  }
  const std::vector<double>& factor = source.pbrMetallicRoughness.baseColorFactor;
  if (factor.size() != 4) fail(field + ".pbrMetallicRoughness.baseColorFactor: expected 4 numbers");
  for (int c = 0; c < 4; ++c) {
    if (!std::isfinite(factor[static_cast<size_t>(c)]))
      fail(field + ".pbrMetallicRoughness.baseColorFactor: expected finite numbers");
    material.base_color[c] = static_cast<float>(std::clamp(factor[static_cast<size_t>(c)], 0.0, 1.0));
  }
  const std::string pbr = field + ".pbrMetallicRoughness";
  material.metallic = unit_factor(source.pbrMetallicRoughness.metallicFactor, pbr + ".metallicFactor");
  material.roughness = unit_factor(source.pbrMetallicRoughness.roughnessFactor, pbr + ".roughnessFactor");
  const nlohmann::json& json_material = document_.root()["materials"][static_cast<size_t>(index)];
  MaterialMappings mappings;
  // Each texture: its Scene texture in the colour space it is read in, and which mapping it uses.
  auto slot = [&](int texture_index, int tex_coord, const nlohmann::json* info, const std::string& at, bool srgb) {
    TextureSlot out;
    if (texture_index < 0) return out;
    out.texture = texture(texture_index, at + ".index", srgb);
    UvMapping mapping;
    mapping.set = tex_coord;
    if (info && info->is_object())
      if (const auto extensions = info->find("extensions"); extensions != info->end() && extensions->is_object())
        if (const auto transform = extensions->find("KHR_texture_transform"); transform != extensions->end())
          read_texture_transform(*transform, at + ".extensions.KHR_texture_transform", mapping);
    if (!mappings.has_first || mappings.first == mapping) {
      mappings.first = mapping;
      mappings.has_first = true;
    } else if (!mappings.has_second || mappings.second == mapping) {
      mappings.second = mapping;
      mappings.has_second = out.second_uv = true;
    } else {
      report_.warnings.push_back(at + ": a third texture coordinate mapping in one material; sampled with the first");
    }
    return out;
  };
  auto info_of = [&](const nlohmann::json& holder, const char* key) -> const nlohmann::json* {
    if (!holder.is_object()) return nullptr;
    const auto found = holder.find(key);
    return found == holder.end() ? nullptr : &*found;
  };
  const nlohmann::json* json_pbr = info_of(json_material, "pbrMetallicRoughness");
  const nlohmann::json empty = nlohmann::json::object();
  const nlohmann::json& pbr_json = json_pbr ? *json_pbr : empty;
  // The base colour comes first: its mapping is the one every mesh has in Vertex::uv.
  const tinygltf::TextureInfo& base = source.pbrMetallicRoughness.baseColorTexture;
  material.base_color_texture =
      slot(base.index, base.texCoord, info_of(pbr_json, "baseColorTexture"), pbr + ".baseColorTexture", true).texture;
  const tinygltf::TextureInfo& mr = source.pbrMetallicRoughness.metallicRoughnessTexture;
  material.metallic_roughness =
      slot(mr.index, mr.texCoord, info_of(pbr_json, "metallicRoughnessTexture"), pbr + ".metallicRoughnessTexture", false);
  const tinygltf::NormalTextureInfo& normal = source.normalTexture;
  material.normal = slot(normal.index, normal.texCoord, info_of(json_material, "normalTexture"), field + ".normalTexture", false);
  // A normal map that could not be decoded is drawn without (a white texel is no normal).
  if (material.normal.present() && material.normal.texture == white_) material.normal = TextureSlot{};
  if (!std::isfinite(normal.scale)) fail(field + ".normalTexture.scale: expected a finite number");
  material.normal_scale = static_cast<float>(normal.scale);
  // Beyond 10^4 the mapped normal lies in the surface already; larger values would overflow the
  // shader's float arithmetic into NaN normals.
  if (std::abs(normal.scale) > 1e4) {
    material.normal_scale = static_cast<float>(std::copysign(1e4, normal.scale));
    report_.warnings.push_back(field + ".normalTexture.scale: " + std::to_string(normal.scale) + " is used as " +
                               std::to_string(material.normal_scale));
  }
  const tinygltf::OcclusionTextureInfo& occlusion = source.occlusionTexture;
  material.occlusion =
      slot(occlusion.index, occlusion.texCoord, info_of(json_material, "occlusionTexture"), field + ".occlusionTexture", false);
  material.occlusion_strength = unit_factor(occlusion.strength, field + ".occlusionTexture.strength");
  const tinygltf::TextureInfo& emissive = source.emissiveTexture;
  material.emissive_texture =
      slot(emissive.index, emissive.texCoord, info_of(json_material, "emissiveTexture"), field + ".emissiveTexture", true);
  if (source.emissiveFactor.size() != 3) fail(field + ".emissiveFactor: expected 3 numbers");
  float strength = 1.0f;
  if (const nlohmann::json* extensions = info_of(json_material, "extensions"))
    if (const nlohmann::json* found = info_of(*extensions, "KHR_materials_emissive_strength")) {
      const std::string at = field + ".extensions.KHR_materials_emissive_strength.emissiveStrength";
      const nlohmann::json* value = info_of(*found, "emissiveStrength");
      if (!found->is_object() || (value && (!value->is_number() || !std::isfinite(value->get<double>()) ||
                                            value->get<double>() < 0.0 || value->get<double>() > 1e6)))
        fail(at + ": expected a number from 0 to 1e6");
      if (value) strength = value->get<float>();
    }
  for (int c = 0; c < 3; ++c)
    material.emissive[c] = unit_factor(source.emissiveFactor[static_cast<size_t>(c)], field + ".emissiveFactor") * strength;
  scene_.materials.push_back(material);
  const int id = static_cast<int>(scene_.materials.size()) - 1;
  uv_mappings_[id] = mappings;
  return materials_[index] = id;
}

// glTF's factors in [0, 1]; out of range is clamped as the validator only warns, non-finite refused.
float MaterialReader::unit_factor(double value, const std::string& field) {
  if (!std::isfinite(value)) fail(field + ": " + std::to_string(value) + "; expected a number from 0 to 1");
  return static_cast<float>(std::clamp(value, 0.0, 1.0));
}

// KHR_texture_transform: uv' = T(offset) R(rotation) S(scale) uv with R taking (u, v) to
// (u cos r + v sin r, -u sin r + v cos r): counter-clockwise as the image is seen, v pointing down
// in glTF's UV space. Khronos' TextureTransformTest sample tells the direction: its arrows reach
// the green markers (the red marker is the opposite rotation). texCoord, when given, replaces the
// texture info's set.
void MaterialReader::read_texture_transform(const nlohmann::json& extension, const std::string& field, UvMapping& mapping) {
  if (!extension.is_object()) fail(field + ": expected an object");
  auto vec2 = [&](const char* key, glm::dvec2 fallback) {
    const auto found = extension.find(key);
    if (found == extension.end()) return fallback;
    if (!found->is_array() || found->size() != 2 || !(*found)[0].is_number() || !(*found)[1].is_number())
      fail(field + "." + key + ": expected 2 numbers");
    const glm::dvec2 value((*found)[0].get<double>(), (*found)[1].get<double>());
    if (!std::isfinite(value.x) || !std::isfinite(value.y)) fail(field + "." + key + ": expected finite numbers");
    return value;
  };
  const glm::dvec2 offset = vec2("offset", glm::dvec2(0.0)), scale = vec2("scale", glm::dvec2(1.0));
  double rotation = 0.0;
  if (const auto found = extension.find("rotation"); found != extension.end()) {
    if (!found->is_number() || !std::isfinite(found->get<double>())) fail(field + ".rotation: expected a finite number");
    rotation = found->get<double>();
  }
  if (const auto found = extension.find("texCoord"); found != extension.end()) {
    if (!found->is_number_unsigned() || found->get<uint64_t>() > 1u << 16)
      fail(field + ".texCoord: " + found->dump() + "; expected a texture coordinate set index");
    mapping.set = found->get<int>();
  }
  const double c = std::cos(rotation), s = std::sin(rotation);
  const glm::dmat3 translation(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);
  const glm::dmat3 rotate(c, -s, 0, s, c, 0, 0, 0, 1);
  const glm::dmat3 scaling(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
  mapping.transform = translation * rotate * scaling;
  mapping.transformed = true;
}

// Scene texture of glTF texture `index` read as colour (`srgb`) or data: a texture used both ways
// (rare) becomes two, since the GPU decodes sRGB by format.
int MaterialReader::texture(int index, const std::string& field, bool srgb) {
  if (static_cast<size_t>(index) >= model_.textures.size())
    fail(field + ": " + std::to_string(index) + " out of range (there are " + std::to_string(model_.textures.size()) + ")");
  if (auto found = textures_.find({index, srgb}); found != textures_.end()) return found->second;
  const tinygltf::Texture& source = model_.textures[static_cast<size_t>(index)];
  const std::string where = "textures[" + std::to_string(index) + "]";
  // A texture without a source (one only an extension such as KHR_texture_basisu supplies) is
  // drawn white, as the warning about the extension says.
  if (source.source < 0) return white_texture();
  const DecodedImage& image = document_.image(source.source, where + ".source");
  // An image that could not be used is drawn white; the document has put the reason in the warnings.
  if (image.rgba.empty()) return white_texture();
  Texture texture;
  texture.srgb = srgb;
  texture.width = image.width;
  texture.height = image.height;
  texture.rgba = image.rgba;
  if (source.sampler >= 0 && static_cast<size_t>(source.sampler) < model_.samplers.size()) {
    const tinygltf::Sampler& sampler = model_.samplers[static_cast<size_t>(source.sampler)];
    texture.mag = sampler.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST ? Filter::nearest : Filter::linear;
    // Absent or outside its list (the schema check warned), minFilter means the default: mipmapped.
    texture.mipmaps = sampler.minFilter != TINYGLTF_TEXTURE_FILTER_NEAREST && sampler.minFilter != TINYGLTF_TEXTURE_FILTER_LINEAR;
    texture.repeat_s = sampler.wrapS != TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    texture.repeat_t = sampler.wrapT != TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
  } else if (source.sampler >= 0) {
    fail(where + ".sampler: " + std::to_string(source.sampler) + " out of range");
  }
  scene_.textures.push_back(std::move(texture));
  return textures_[{index, srgb}] = static_cast<int>(scene_.textures.size()) - 1;
}

int MaterialReader::white_texture() {
  if (white_ < 0) {
    Texture white;
    white.width = white.height = 1;
    white.rgba = {255, 255, 255, 255};
    white.mipmaps = false;
    scene_.textures.push_back(std::move(white));
    white_ = static_cast<int>(scene_.textures.size()) - 1;
  }
  return white_;
}

}  // namespace scene::gltf
