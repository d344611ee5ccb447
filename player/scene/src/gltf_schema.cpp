#include "gltf_schema.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>

namespace scene::gltf {
namespace fs = std::filesystem;
using nlohmann::json;
namespace {

constexpr int64_t kMaxSafeInteger = (int64_t{1} << 53) - 1;  // glTF's integers are JSON numbers

std::string brief(const json& value) {
  std::string text = value.dump();
  return text.size() > 40 ? text.substr(0, 37) + "..." : text;
}

class SchemaCheck {
 public:
  // `warnings` receives what glTF-Validator reports as a warning and the loader can do without:
  // a sampler value outside its list means the default for that field.
  SchemaCheck(const json& root, std::vector<std::string>& warnings) : root_(root), warnings_(warnings) {}

  std::string run() {
    if (!root_.is_object()) return "the top level: expected a JSON object";
    asset();
    for (const char* name :
         {"accessors", "bufferViews", "buffers", "images", "materials", "meshes", "nodes", "samplers", "scenes", "textures"})
      objects(name);
    if (!problem_.empty()) return problem_;
    index(root_, "scene", "scene", "scenes");
    each("scenes", [&](const json& scene, const std::string& at) { index_array(scene, "nodes", at, "nodes"); });
    each("nodes", [&](const json& node, const std::string& at) {
      index_array(node, "children", at, "nodes");
      index(node, "mesh", at, "meshes");
    });
    each("meshes", [&](const json& mesh, const std::string& at) {
      const json* primitives = array_of(mesh, "primitives", at);
      if (!primitives) return;
      for (size_t p = 0; p < primitives->size() && problem_.empty(); ++p) {
        const json& primitive = (*primitives)[p];
        const std::string where = at + ".primitives[" + std::to_string(p) + "]";
        if (!primitive.is_object()) {
          fail_once(where + ": expected an object");
          return;
        }
        if (const auto attributes = primitive.find("attributes"); attributes != primitive.end())
          accessor_map(*attributes, where + ".attributes");
        index(primitive, "indices", where, "accessors");
        index(primitive, "material", where, "materials");
        integer(primitive, "mode", where, 0, 6, false);
        if (const json* targets = array_of(primitive, "targets", where))
          for (size_t t = 0; t < targets->size(); ++t) accessor_map((*targets)[t], where + ".targets[" + std::to_string(t) + "]");
      }
    });
    each("accessors", [&](const json& accessor, const std::string& at) {
      index(accessor, "bufferView", at, "bufferViews");
      integer(accessor, "byteOffset", at, 0, kMaxSafeInteger, false);
      one_of(accessor, "componentType", at, {5120, 5121, 5122, 5123, 5125, 5126}, true);
      integer(accessor, "count", at, 1, kMaxSafeInteger, true);
      if (problem_.empty() && (!accessor.contains("type") || !accessor["type"].is_string()))
        fail_once(at + ".type: expected one of \"SCALAR\", \"VEC2\", \"VEC3\", \"VEC4\", \"MAT2\", \"MAT3\", \"MAT4\"");
      if (const auto sparse = accessor.find("sparse"); sparse != accessor.end() && problem_.empty()) {
        const std::string where = at + ".sparse";
        if (!sparse->is_object()) return fail_once(where + ": expected an object");
        integer(*sparse, "count", where, 1, INT32_MAX, true);
        for (const char* part : {"indices", "values"}) {
          const std::string place = where + "." + part;
          const auto found = sparse->find(part);
          if (found == sparse->end() || !found->is_object()) return fail_once(place + ": expected an object");
          index(*found, "bufferView", place, "bufferViews", true);
          integer(*found, "byteOffset", place, 0, INT32_MAX, false);
          if (std::string(part) == "indices") one_of(*found, "componentType", place, {5121, 5123, 5125}, true);
        }
      }
    });
    each("bufferViews", [&](const json& view, const std::string& at) {
      index(view, "buffer", at, "buffers", true);
      integer(view, "byteOffset", at, 0, kMaxSafeInteger, false);
      integer(view, "byteLength", at, 1, kMaxSafeInteger, true);
      if (const auto stride = view.find("byteStride"); stride != view.end() && problem_.empty()) {
        integer(view, "byteStride", at, 4, 252, false);
        if (problem_.empty() && stride->get<int64_t>() % 4 != 0)
          fail_once(at + ".byteStride: " + brief(*stride) + " is not a multiple of 4; expected 4, 8, .. 252");
      }
      if (!problem_.empty()) return;
      // Fits its buffer's declared length; tinygltf checks each buffer's bytes against that length.
      const int64_t offset = view.value("byteOffset", int64_t{0}), length = view["byteLength"].get<int64_t>();
      const json& buffer = root_["buffers"][view["buffer"].get<size_t>()];
      if (buffer.contains("byteLength") && buffer["byteLength"].is_number_integer() &&
          offset + length > buffer["byteLength"].get<int64_t>())
        fail_once(at + ": bytes " + std::to_string(offset) + ".." + std::to_string(offset + length) + " lie beyond buffers[" +
                  std::to_string(view["buffer"].get<size_t>()) + "].byteLength " +
                  std::to_string(buffer["byteLength"].get<int64_t>()));
    });
    each("buffers",
         [&](const json& buffer, const std::string& at) { integer(buffer, "byteLength", at, 1, kMaxSafeInteger, true); });
    each("images", [&](const json& image, const std::string& at) { index(image, "bufferView", at, "bufferViews"); });
    each("textures", [&](const json& texture, const std::string& at) {
      index(texture, "sampler", at, "samplers");
      index(texture, "source", at, "images");
    });
    each("samplers", [&](const json& sampler, const std::string& at) {
      sampler_value(sampler, "magFilter", at, {9728, 9729}, "linear");
      sampler_value(sampler, "minFilter", at, {9728, 9729, 9984, 9985, 9986, 9987}, "mipmapped linear");
      sampler_value(sampler, "wrapS", at, {33071, 33648, 10497}, "repeat");
      sampler_value(sampler, "wrapT", at, {33071, 33648, 10497}, "repeat");
    });
    each("materials", [&](const json& material, const std::string& at) {
      auto texture_info = [&](const json& holder, const char* key, const std::string& where) {
        const auto info = holder.find(key);
        if (info == holder.end() || !problem_.empty()) return;
        const std::string place = where + "." + key;
        if (!info->is_object()) return fail_once(place + ": expected an object");
        index(*info, "index", place, "textures", true);
        integer(*info, "texCoord", place, 0, INT32_MAX, false);
      };
      if (const auto pbr = material.find("pbrMetallicRoughness"); pbr != material.end()) {
        if (!pbr->is_object()) return fail_once(at + ".pbrMetallicRoughness: expected an object");
        texture_info(*pbr, "baseColorTexture", at + ".pbrMetallicRoughness");
        texture_info(*pbr, "metallicRoughnessTexture", at + ".pbrMetallicRoughness");
      }
      for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"}) texture_info(material, key, at);
    });
    return problem_;
  }

 private:
  void fail_once(const std::string& message) {
    if (problem_.empty()) problem_ = message;
  }

  // asset.version is required; the player reads glTF 2 (any 2.x, whose minor versions only add
  // things a 2.0 reader may skip) and refuses a file whose minVersion asks for more than 2.0.
  void asset() {
    const auto found = root_.find("asset");
    if (found == root_.end() || !found->is_object()) return fail_once("asset: missing; expected {\"version\": \"2.0\"}");
    auto parse = [](const json& value, int& major, int& minor) {
      if (!value.is_string()) return false;
      const std::string text = value.get<std::string>();
      char tail = 0;
      return std::sscanf(text.c_str(), "%d.%d%c", &major, &minor, &tail) == 2 && text.find_first_of(" +-") == std::string::npos;
    };
    int major = 0, minor = 0;
    const auto version = found->find("version");
    if (version == found->end()) return fail_once("asset.version: missing; expected \"2.0\"");
    if (!parse(*version, major, minor))
      return fail_once("asset.version: " + brief(*version) + " is not a version; expected \"2.0\"");
    if (major != 2) return fail_once("asset.version: " + brief(*version) + " is not glTF 2; expected \"2.0\" (or another 2.x)");
    if (const auto min_version = found->find("minVersion"); min_version != found->end()) {
      int min_major = 0, min_minor = 0;
      if (!parse(*min_version, min_major, min_minor))
        return fail_once("asset.minVersion: " + brief(*min_version) + " is not a version; expected \"2.0\"");
      if (min_major != 2 || min_minor != 0)
        return fail_once("asset.minVersion: " + brief(*min_version) + " asks for more than this player reads; expected \"2.0\"");
      if (min_minor > minor) return fail_once("asset.minVersion: " + brief(*min_version) + " is above asset.version");
    }
  }

  void objects(const char* name) {
    const auto found = root_.find(name);
    if (found == root_.end() || !problem_.empty()) return;
    if (!found->is_array()) return fail_once(std::string(name) + ": expected an array");
    for (size_t i = 0; i < found->size(); ++i)
      if (!(*found)[i].is_object()) return fail_once(std::string(name) + "[" + std::to_string(i) + "]: expected an object");
  }

  template <typename F>
  void each(const char* name, F check) {
    const auto found = root_.find(name);
    if (found == root_.end()) return;
    for (size_t i = 0; i < found->size() && problem_.empty(); ++i)
      check((*found)[i], std::string(name) + "[" + std::to_string(i) + "]");
  }

  size_t size_of(const char* name) const {
    const auto found = root_.find(name);
    return found == root_.end() ? 0 : found->size();
  }

  const json* array_of(const json& object, const char* key, const std::string& where) {
    const auto found = object.find(key);
    if (found == object.end() || !problem_.empty()) return nullptr;
    if (!found->is_array()) {
      fail_once(where + "." + key + ": expected an array");
      return nullptr;
    }
    return &*found;
  }

  // An integer property in [min, max]; floats ("count": 3.5), strings ("count": "3") and numbers
  // beyond 2^64 (which JSON parsers read as floats) are all "expected an integer".
  bool integer(const json& object, const std::string& key, const std::string& where, int64_t min, int64_t max, bool required) {
    if (!problem_.empty()) return false;
    const auto found = object.find(key);
    const std::string field = where + "." + key;
    const std::string range = "an integer from " + std::to_string(min) + " to " + std::to_string(max);
    if (found == object.end()) {
      if (required) fail_once(field + ": missing; expected " + range);
      return false;
    }
    if (!found->is_number_integer()) {
      fail_once(field + ": " + brief(*found) + " is not an integer; expected " + range);
      return false;
    }
    const bool in_range = found->is_number_unsigned() ? found->get<uint64_t>() <= static_cast<uint64_t>(max) &&
                                                            static_cast<int64_t>(found->get<uint64_t>()) >= min
                                                      : found->get<int64_t>() >= min && found->get<int64_t>() <= max;
    if (!in_range) {
      fail_once(field + ": " + brief(*found) + " is out of range; expected " + range);
      return false;
    }
    return true;
  }

  void one_of(const json& object, const char* key, const std::string& where, std::initializer_list<int64_t> allowed,
              bool required) {
    if (!integer(object, key, where, 0, kMaxSafeInteger, required)) return;
    const int64_t value = object[key].get<int64_t>();
    if (std::find(allowed.begin(), allowed.end(), value) != allowed.end()) return;
    std::string list;
    for (int64_t a : allowed) list += (list.empty() ? "" : ", ") + std::to_string(a);
    fail_once(where + "." + key + ": " + std::to_string(value) + " is not allowed; expected one of " + list);
  }

  // An integer, and when outside `allowed` a warning: the texture samples with the default.
  void sampler_value(const json& object, const char* key, const std::string& where, std::initializer_list<int64_t> allowed,
                     const char* fallback) {
    if (!integer(object, key, where, 0, kMaxSafeInteger, false)) return;
    const int64_t value = object[key].get<int64_t>();
    if (std::find(allowed.begin(), allowed.end(), value) != allowed.end()) return;
    std::string list;
    for (int64_t a : allowed) list += (list.empty() ? "" : ", ") + std::to_string(a);
    warnings_.push_back(where + "." + key + ": " + std::to_string(value) + " is not one of " + list + "; " + fallback +
                        " is used");
  }

  void index(const json& object, const std::string& key, const std::string& where, const char* target, bool required = false) {
    const std::string field = where == key ? key : where + "." + key;
    if (!problem_.empty()) return;
    const auto found = object.find(key);
    if (found == object.end()) {
      if (required) fail_once(field + ": missing; expected an index into " + target);
      return;
    }
    check_index(*found, field, target);
  }

  void check_index(const json& value, const std::string& field, const char* target) {
    const size_t count = size_of(target);
    const bool negative = value.is_number_integer() && !value.is_number_unsigned() && value.get<int64_t>() < 0;
    if (!value.is_number_integer() || negative || value.get<uint64_t>() >= count)
      fail_once(field + ": " + brief(value) + " is out of range; expected an index into " + target + " (there are " +
                std::to_string(count) + ")");
  }

  void index_array(const json& object, const char* key, const std::string& where, const char* target) {
    const json* values = array_of(object, key, where);
    if (!values) return;
    for (size_t i = 0; i < values->size() && problem_.empty(); ++i)
      check_index((*values)[i], where + "." + key + "[" + std::to_string(i) + "]", target);
  }

  // A name -> accessor map (attributes, a morph target).
  void accessor_map(const json& object, const std::string& field) {
    if (!problem_.empty()) return;
    if (!object.is_object()) return fail_once(field + ": expected an object");
    for (const auto& [name, value] : object.items()) {
      if (!problem_.empty()) return;
      check_index(value, field + "." + name, "accessors");
    }
  }

  const json& root_;
  std::vector<std::string>& warnings_;
  std::string problem_;
};

}  // namespace

std::string schema_problem(const json& root, std::vector<std::string>& warnings) {
  return SchemaCheck(root, warnings).run();
}

void integral_floats_to_integers(json& value) {
  if (value.is_number_float()) {
    const double number = value.get<double>();
    // 2^53: beyond it a double no longer holds every integer, and glTF's integers stop there too.
    // Non-negative integers become unsigned, as the parser reads "3", so "3.0" passes every check "3" does.
    if (std::trunc(number) == number && std::abs(number) <= 9007199254740991.0) {
      if (number >= 0)
        value = static_cast<uint64_t>(number);
      else
        value = static_cast<int64_t>(number);
    }
  } else if (value.is_structured()) {
    for (json& element : value) integral_floats_to_integers(element);
  }
}

}  // namespace scene::gltf
