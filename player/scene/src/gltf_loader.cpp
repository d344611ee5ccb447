#include "scene/gltf_loader.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <png.h>
#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <set>
#include <system_error>

namespace scene {
namespace fs = std::filesystem;
namespace {

// Far above any scene a single-board computer can draw, low enough that sizes cannot overflow.
constexpr size_t kMaxElements = size_t{1} << 28;

struct LoadError {
  std::string message;
};

[[noreturn]] void fail(const std::string& message) { throw LoadError{message}; }

// --- File access confined to the scene's folder -------------------------------------------------

struct Confinement {
  fs::path root;  // canonical folder of the scene file
};

bool inside(const fs::path& root, const fs::path& candidate) {
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(candidate, ec);
  if (ec) return false;
  auto [root_end, unused] = std::mismatch(root.begin(), root.end(), resolved.begin(), resolved.end());
  (void)unused;
  return root_end == root.end();
}

// Reports files outside the folder as existing so that the read below refuses them by name,
// rather than tinygltf saying only "file not found".
bool confined_exists(const std::string& path, void*) {
  std::error_code ec;
  return fs::is_regular_file(path, ec);
}

std::string confined_expand(const std::string& path, void*) { return path; }

bool confined_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  const auto* confinement = static_cast<Confinement*>(user);
  if (!inside(confinement->root, path)) {
    if (err) *err += "'" + path + "' lies outside the scene's folder " + confinement->root.string() + "; ";
    return false;
  }
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    if (err) *err += "cannot open '" + path + "'; ";
    return false;
  }
  out->assign(std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>());
  return true;
}

bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "the loader never writes files; ";
  return false;
}

// --- Bytes before tinygltf sees them ---------------------------------------------------------------

std::string hex32(uint32_t value) {
  char text[11];
  std::snprintf(text, sizeof text, "0x%08X", value);
  return text;
}

uint32_t u32_at(const std::string& bytes, size_t at) {
  uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, 4);
  return value;  // GLB is little-endian, like every board this player runs on
}

constexpr uint32_t kChunkJson = 0x4E4F534A, kChunkBin = 0x004E4942;

struct Glb {
  std::string json;
  std::string bin;
  bool has_bin = false;
};

// The GLB layout (glTF 2.0, 4.4): checked here because tinygltf reads chunk 1 at whatever offset
// chunk 0's length gives, and an empty file makes its reader index an empty vector.
std::string split_glb(const std::string& bytes, Glb& out, std::vector<std::string>& warnings) {
  if (bytes.size() < 12)
    return "the file is " + std::to_string(bytes.size()) + " bytes; expected a 12-byte GLB header and a JSON chunk";
  if (bytes.compare(0, 4, "glTF") != 0) return "bytes 0..3 are not the GLB magic 'glTF'";
  if (const uint32_t version = u32_at(bytes, 4); version != 2)
    return "GLB header version " + std::to_string(version) + "; expected 2";
  if (const uint32_t length = u32_at(bytes, 8); length != bytes.size())
    return "GLB header length " + std::to_string(length) + " differs from the file's " + std::to_string(bytes.size()) +
           " bytes";
  size_t at = 12;
  bool has_json = false;
  for (int chunk = 0; at < bytes.size(); ++chunk) {
    const std::string where = "GLB chunk " + std::to_string(chunk) + " at byte " + std::to_string(at);
    if (bytes.size() - at < 8) return where + ": its 8-byte header runs past the end of the file";
    const uint32_t length = u32_at(bytes, at), type = u32_at(bytes, at + 4);
    if (length > bytes.size() - at - 8)
      return where + ": length " + std::to_string(length) + " runs past the end of the file (" +
             std::to_string(bytes.size() - at - 8) + " bytes left)";
    if (length % 4 != 0) return where + ": length " + std::to_string(length) + " is not a multiple of 4";
    const std::string data = bytes.substr(at + 8, length);
    if (chunk == 0 && type != kChunkJson) return where + ": type " + hex32(type) + "; expected JSON (0x4E4F534A) first";
    if (chunk == 0) {
      out.json = data;
      has_json = true;
    } else if (type == kChunkJson) {
      return where + ": a second JSON chunk; expected one";
    } else if (type == kChunkBin) {
      if (chunk != 1) return where + ": a BIN chunk must directly follow the JSON chunk";
      out.bin = data;
      out.has_bin = true;
    } else {
      // The spec: "client implementations must ignore chunks with unknown types".
      warnings.push_back(where + ": unknown chunk type " + hex32(type) + "; ignored");
    }
    at += 8 + length;
  }
  if (!has_json) return "the GLB file has no JSON chunk";
  return {};
}

// The same layout rebuilt from checked parts, for tinygltf's reader (which needs BIN right after JSON).
std::string join_glb(const Glb& glb) {
  std::string json = glb.json;
  while (json.size() % 4) json += ' ';
  std::string bytes = "glTF";
  auto put = [&](uint32_t value) { bytes.append(reinterpret_cast<const char*>(&value), 4); };
  const bool bin = glb.has_bin && !glb.bin.empty();
  put(2);
  put(static_cast<uint32_t>(12 + 8 + json.size() + (bin ? 8 + glb.bin.size() : 0)));
  put(static_cast<uint32_t>(json.size()));
  put(kChunkJson);
  bytes += json;
  if (bin) {
    put(static_cast<uint32_t>(glb.bin.size()));
    put(kChunkBin);
    bytes += glb.bin;
  }
  return bytes;
}

// Bracket depth outside strings, counted before any parser runs: tinygltf converts the parsed JSON
// to its own values by recursion, so 200,000 nested arrays would otherwise overflow the stack.
std::string nesting_problem(const std::string& text) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        return "JSON nests deeper than " + std::to_string(kMaxJsonDepth) + " levels at byte " + std::to_string(i) +
               "; expected at most " + std::to_string(kMaxJsonDepth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return {};
}

// --- The parts of glTF's JSON schema the player relies on -----------------------------------------
// tinygltf keeps a default for a property whose value has the wrong type or sign (a negative
// byteOffset silently becomes 0) and does not range-check indices it follows itself (an image's
// bufferView is read without a bounds check), so these are checked on the JSON first.

using nlohmann::json;

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
    for (const char* name : {"accessors", "bufferViews", "buffers", "images", "materials", "meshes", "nodes", "samplers",
                             "scenes", "textures"})
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
        integer(*sparse, "count", where, 1, kMaxSafeInteger, true);
        for (const char* part : {"indices", "values"}) {
          const std::string place = where + "." + part;
          const auto found = sparse->find(part);
          if (found == sparse->end() || !found->is_object()) return fail_once(place + ": expected an object");
          index(*found, "bufferView", place, "bufferViews", true);
          integer(*found, "byteOffset", place, 0, kMaxSafeInteger, false);
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
        fail_once(at + ": bytes " + std::to_string(offset) + ".." + std::to_string(offset + length) +
                  " lie beyond buffers[" + std::to_string(view["buffer"].get<size_t>()) + "].byteLength " +
                  std::to_string(buffer["byteLength"].get<int64_t>()));
    });
    each("buffers", [&](const json& buffer, const std::string& at) {
      integer(buffer, "byteLength", at, 1, kMaxSafeInteger, true);
    });
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
        integer(*info, "texCoord", place, 0, kMaxSafeInteger, false);
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
    if (major != 2)
      return fail_once("asset.version: " + brief(*version) + " is not glTF 2; expected \"2.0\" (or another 2.x)");
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

// External files may only be named relative to the scene's folder and may not climb out of it.
std::string uri_problem(const json& root) {
  for (const char* array : {"buffers", "images"}) {
    const auto found = root.find(array);
    if (found == root.end() || !found->is_array()) continue;
    for (size_t i = 0; i < found->size(); ++i) {
      const json& entry = (*found)[i];
      if (!entry.is_object() || !entry.contains("uri") || !entry["uri"].is_string()) continue;
      const std::string uri = entry["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0) continue;
      const std::string field = std::string(array) + "[" + std::to_string(i) + "].uri";
      if (uri.empty()) return field + ": empty; expected a file inside the scene's folder";
      if (uri.find("://") != std::string::npos)
        return field + ": '" + uri + "' is a URL; expected a file inside the scene's folder";
      const fs::path path(uri);
      if (path.is_absolute() || uri.front() == '/' || uri.front() == '\\')
        return field + ": '" + uri + "' is an absolute path; expected a path relative to the scene's folder";
      int depth = 0;
      for (const fs::path& part : path) {
        if (part == "..") --depth;
        else if (part != "." && !part.empty()) ++depth;
        if (depth < 0) return field + ": '" + uri + "' escapes the scene's folder";
      }
    }
  }
  return {};
}

// --- Images: PNG through libpng, JPEG through OpenImageIO ----------------------------------------
// An image that cannot be used (not PNG or JPEG, corrupt, truncated, too large) does not stop the
// scene: its texture is drawn white and the report says why, so a kiosk still shows the geometry.
// Nothing from the decoders reaches stderr: OpenImageIO's PNG reader lets libpng print "libpng
// error: ..." itself, so PNG goes through libpng's simplified API, which keeps every message in
// png_image::message; OpenImageIO's JPEG reader routes libjpeg's messages to its own error, which
// is read and dropped. Either way the one line is ours.

struct ImageContext {
  const LoadOptions* options = nullptr;
  std::map<int, std::string> problems;  // image index -> why it is drawn white
};

bool load_image(tinygltf::Image* image, const int index, std::string*, std::string*, int, int,
                const unsigned char* bytes, int size, void* user) {
  auto& context = *static_cast<ImageContext*>(user);
  auto skip = [&](const std::string& what) {
    context.problems[index] = what;
    image->image.clear();
    image->width = image->height = 0;
    return true;  // tinygltf would drop the whole scene on false
  };
  if (size < 4) return skip("image data is empty or truncated");
  // OpenImageIO picks the reader by file extension; glTF images are PNG or JPEG by magic number.
  const bool png = bytes[0] == 0x89 && bytes[1] == 'P', jpeg = bytes[0] == 0xFF && bytes[1] == 0xD8;
  if (!png && !jpeg) return skip("expected PNG or JPEG data");
  const std::string kind = png ? "PNG" : "JPEG";
  const std::string corrupt = "the " + kind + " data cannot be decoded (corrupt or truncated)";
  // From the header alone: the size is checked before a single pixel is decoded or allocated.
  auto size_problem = [&](uint64_t width, uint64_t height) -> std::string {
    const uint64_t limit = static_cast<uint64_t>(context.options->max_texture_size);
    const std::string dimensions = kind + " of " + std::to_string(width) + "x" + std::to_string(height);
    if (width == 0 || height == 0 || width > limit || height > limit)
      return dimensions + "; expected 1.." + std::to_string(limit) + " pixels per side";
    const uint64_t decoded = width * height * 4;
    if (decoded > context.options->image_budget_bytes)
      return dimensions + " needs " + std::to_string(decoded >> 20) + " MiB decoded; expected at most " +
             std::to_string(context.options->image_budget_bytes >> 20) + " MiB per image";
    return {};
  };
  auto finish = [&](int width, int height, std::vector<unsigned char> pixels) {
    image->width = width;
    image->height = height;
    image->component = 4;
    image->bits = 8;
    image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    image->image = std::move(pixels);
    return true;
  };
  if (png) {
    png_image decoder{};
    decoder.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&decoder, bytes, static_cast<size_t>(size))) return skip(corrupt);
    if (const std::string problem = size_problem(decoder.width, decoder.height); !problem.empty()) {
      png_image_free(&decoder);
      return skip(problem);
    }
    decoder.format = PNG_FORMAT_RGBA;  // grey, palette and 16-bit files all become 8-bit sRGB RGBA
    std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(decoder));
    const int width = static_cast<int>(decoder.width), height = static_cast<int>(decoder.height);
    if (!png_image_finish_read(&decoder, nullptr, pixels.data(), 0, nullptr)) return skip(corrupt);
    return finish(width, height, std::move(pixels));
  }
  OIIO::Filesystem::IOMemReader memory(const_cast<unsigned char*>(bytes), static_cast<size_t>(size));
  auto input = OIIO::ImageInput::open("image.jpg", nullptr, &memory);
  if (!input) {
    (void)OIIO::geterror();  // clears the thread's message so it cannot surface later
    return skip(corrupt);
  }
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width <= 0 || spec.height <= 0) return skip(corrupt);
  if (const std::string problem = size_problem(uint64_t(spec.width), uint64_t(spec.height)); !problem.empty())
    return skip(problem);
  std::vector<unsigned char> pixels(size_t(spec.width) * size_t(spec.height) * 4, 255);
  const int channels = std::min(spec.nchannels, 4);
  const bool read = input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data(), 4);
  const bool clean = !input->has_error();
  (void)input->geterror();
  (void)OIIO::geterror();
  // libjpeg decodes a truncated file to grey with only a warning: any message counts as a failure.
  if (!read || !clean) return skip(corrupt);
  if (channels < 3) {  // grey (+ alpha): spread grey over RGB
    for (size_t p = 0; p < pixels.size(); p += 4) {
      if (channels == 2) pixels[p + 3] = pixels[p + 1];
      pixels[p + 1] = pixels[p + 2] = pixels[p];
    }
  }
  return finish(spec.width, spec.height, std::move(pixels));
}

// --- Accessors -------------------------------------------------------------------------------------

size_t component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

struct View {
  const unsigned char* data = nullptr;  // null: the accessor has no buffer view, all zeros
  size_t stride = 0;
  size_t count = 0;
  int component_type = 0;
  int components = 0;
  bool normalized = false;
};

// Checks accessor `index` against the expected shapes and every byte it spans against its buffer view
// and buffer. `field` names the place that refers to it, e.g. "meshes[0].primitives[1].attributes.POSITION".
View checked_view(const tinygltf::Model& model, int index, const std::string& field, std::initializer_list<int> types,
                  int components) {
  if (index < 0 || static_cast<size_t>(index) >= model.accessors.size())
    fail(field + ": accessor index " + std::to_string(index) + " out of range (there are " +
         std::to_string(model.accessors.size()) + ")");
  const tinygltf::Accessor& accessor = model.accessors[static_cast<size_t>(index)];
  const std::string where = field + " (accessors[" + std::to_string(index) + "])";
  if (accessor.sparse.isSparse) fail(where + ": sparse accessors are not supported");
  if (std::find(types.begin(), types.end(), accessor.componentType) == types.end()) {
    std::string allowed;
    for (int type : types) allowed += (allowed.empty() ? "" : ", ") + std::to_string(type);
    fail(where + ": componentType " + std::to_string(accessor.componentType) + " is not allowed here; expected " +
         (types.size() == 1 ? "" : "one of ") + allowed);
  }
  const int actual_components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(accessor.type));
  if (actual_components != components)
    fail(where + ": expected " + std::to_string(components) + " components per element, got " +
         std::to_string(actual_components));
  if (accessor.count == 0) fail(where + ": count is 0");
  if (accessor.count > kMaxElements)
    fail(where + ": count " + std::to_string(accessor.count) + " exceeds the limit of " + std::to_string(kMaxElements) +
         " elements");
  View view;
  view.count = accessor.count;
  view.component_type = accessor.componentType;
  view.components = components;
  view.normalized = accessor.normalized;
  const size_t element = component_size(accessor.componentType) * static_cast<size_t>(components);
  if (accessor.bufferView < 0) return view;  // spec: zeros
  if (static_cast<size_t>(accessor.bufferView) >= model.bufferViews.size())
    fail(where + ": bufferView " + std::to_string(accessor.bufferView) + " out of range");
  const tinygltf::BufferView& buffer_view = model.bufferViews[static_cast<size_t>(accessor.bufferView)];
  if (buffer_view.buffer < 0 || static_cast<size_t>(buffer_view.buffer) >= model.buffers.size())
    fail(where + ": bufferViews[" + std::to_string(accessor.bufferView) + "].buffer out of range");
  const tinygltf::Buffer& buffer = model.buffers[static_cast<size_t>(buffer_view.buffer)];
  if (buffer_view.byteOffset > buffer.data.size() || buffer_view.byteLength > buffer.data.size() - buffer_view.byteOffset)
    fail(where + ": bufferViews[" + std::to_string(accessor.bufferView) + "] spans bytes " +
         std::to_string(buffer_view.byteOffset) + ".." + std::to_string(buffer_view.byteOffset + buffer_view.byteLength) +
         " of a buffer of " + std::to_string(buffer.data.size()) + " bytes");
  view.stride = buffer_view.byteStride != 0 ? buffer_view.byteStride : element;
  if (view.stride < element)
    fail(where + ": bufferViews[" + std::to_string(accessor.bufferView) + "].byteStride " + std::to_string(view.stride) +
         " is smaller than an element of " + std::to_string(element) + " bytes");
  // glTF 2.0, 3.6.2.4: every component starts at a multiple of its size.
  if ((buffer_view.byteOffset + accessor.byteOffset) % component_size(accessor.componentType) != 0)
    fail(where + ": starts at byte " + std::to_string(buffer_view.byteOffset + accessor.byteOffset) +
         " of its buffer; expected a multiple of the component size " +
         std::to_string(component_size(accessor.componentType)));
  // count <= kMaxElements and stride <= 252 (schema-checked) keep the product far from overflow;
  // the offset is compared first so the sum cannot wrap either.
  if (accessor.byteOffset > buffer_view.byteLength)
    fail(where + ": byteOffset " + std::to_string(accessor.byteOffset) + " lies beyond its buffer view of " +
         std::to_string(buffer_view.byteLength) + " bytes");
  const size_t span = accessor.byteOffset + view.stride * (accessor.count - 1) + element;
  if (span > buffer_view.byteLength)
    fail(where + ": needs " + std::to_string(span) + " bytes but its buffer view has " +
         std::to_string(buffer_view.byteLength));
  view.data = buffer.data.data() + buffer_view.byteOffset + accessor.byteOffset;
  return view;
}

double component(const View& view, size_t element, int c) {
  if (!view.data) return 0.0;
  const unsigned char* at = view.data + element * view.stride + static_cast<size_t>(c) * component_size(view.component_type);
  auto read = [&](auto type_tag) {
    decltype(type_tag) value;
    std::memcpy(&value, at, sizeof value);
    return value;
  };
  switch (view.component_type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return read(float{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return view.normalized ? read(uint8_t{}) / 255.0 : read(uint8_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return view.normalized ? read(uint16_t{}) / 65535.0 : read(uint16_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return read(uint32_t{});
    case TINYGLTF_COMPONENT_TYPE_BYTE: return view.normalized ? std::max(read(int8_t{}) / 127.0, -1.0) : read(int8_t{});
    case TINYGLTF_COMPONENT_TYPE_SHORT: return view.normalized ? std::max(read(int16_t{}) / 32767.0, -1.0) : read(int16_t{});
    default: return 0.0;
  }
}

template <int N>
std::vector<glm::vec<N, float>> read_floats(const tinygltf::Model& model, int index, const std::string& field,
                                            std::initializer_list<int> types) {
  const View view = checked_view(model, index, field, types, N);
  std::vector<glm::vec<N, float>> values(view.count);
  for (size_t i = 0; i < view.count; ++i)
    for (int c = 0; c < N; ++c) {
      const double value = component(view, i, c);
      if (!std::isfinite(value) || std::abs(value) > 3.0e38)
        fail(field + ": element " + std::to_string(i) + " component " + std::to_string(c) + " is " +
             std::to_string(value) + ", expected a finite number");
      values[i][c] = static_cast<float>(value);
    }
  return values;
}

// --- Scene assembly ------------------------------------------------------------------------------

class Builder {
 public:
  Builder(const tinygltf::Model& model, LoadReport& report) : model_(model), report_(report) {
    scene_.materials.push_back(Material{});  // index 0: glTF's default material
  }

  Scene build(const std::string& name) {
    scene_.name = name;
    for (const std::string& extension : model_.extensionsRequired)
      fail("extensionsRequired: '" + extension + "' is not supported by this player");
    const tinygltf::Scene* shown = nullptr;
    int shown_index = 0;
    if (!model_.scenes.empty()) {
      const int index = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (static_cast<size_t>(index) >= model_.scenes.size())
        fail("scene: " + std::to_string(index) + " out of range (there are " + std::to_string(model_.scenes.size()) + ")");
      shown = &model_.scenes[static_cast<size_t>(index)];
      shown_index = index;
    }
    // glTF allows a file without scenes ("nothing to render at load time", 3.5.1): the kiosk has
    // nothing it could rightly choose to show, so it says so rather than guessing at root nodes.
    if (!shown || shown->nodes.empty()) fail("scenes: the file has no scene with nodes to show");
    visit(shown->nodes, "scenes[" + std::to_string(shown_index) + "].nodes");
    if (scene_.instances.empty()) fail("meshes: the scene contains no triangles to render");
    update_bounds(scene_);
    if (!std::isfinite(scene_.bounds.radius()))
      fail("nodes: the transformed scene bounds are not finite (a transform overflows)");
    return std::move(scene_);
  }

 private:
  static glm::dmat4 local_transform(const tinygltf::Node& node, const std::string& where) {
    auto check = [&](const std::vector<double>& values, const char* field) {
      for (double value : values)
        if (!std::isfinite(value)) fail(where + "." + field + ": expected finite numbers");
    };
    check(node.matrix, "matrix");
    check(node.translation, "translation");
    check(node.rotation, "rotation");
    check(node.scale, "scale");
    if (node.matrix.size() == 16) return glm::make_mat4(node.matrix.data());
    glm::dmat4 transform(1.0);
    if (node.translation.size() == 3) transform = glm::translate(transform, glm::make_vec3(node.translation.data()));
    if (node.rotation.size() == 4) {
      const glm::dquat rotation(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
      transform *= glm::mat4_cast(glm::normalize(rotation));
    }
    if (node.scale.size() == 3) transform = glm::scale(transform, glm::make_vec3(node.scale.data()));
    return transform;
  }

  // Depth-first over the node tree with an explicit stack: a valid file may chain 100,000 nodes,
  // far deeper than the thread's stack allows recursion. on_path marks the nodes from the root to
  // the current one (a child among them is a cycle), seen every node entered (a second entry is a
  // second parent); both are flags per node, so a deep chain costs linear time.
  void visit(const std::vector<int>& roots, const std::string& roots_field) {
    struct Frame {
      int node;
      glm::dmat4 world;
      size_t next_child;
    };
    std::vector<Frame> stack;
    std::vector<char> on_path(model_.nodes.size(), 0), seen(model_.nodes.size(), 0);
    auto enter = [&](int index, const glm::dmat4& parent, const std::string& field) {
      if (index < 0 || static_cast<size_t>(index) >= model_.nodes.size())
        fail(field + ": node index " + std::to_string(index) + " out of range (there are " +
             std::to_string(model_.nodes.size()) + ")");
      const size_t at = static_cast<size_t>(index);
      if (on_path[at]) fail("nodes[" + std::to_string(index) + "].children: the node hierarchy has a cycle through this node");
      if (seen[at]) fail("nodes[" + std::to_string(index) + "]: the node has more than one parent (glTF requires a tree)");
      seen[at] = on_path[at] = 1;
      const std::string where = "nodes[" + std::to_string(index) + "]";
      const tinygltf::Node& node = model_.nodes[at];
      const glm::dmat4 world = parent * local_transform(node, where);
      if (node.mesh >= 0) {
        if (static_cast<size_t>(node.mesh) >= model_.meshes.size())
          fail(where + ".mesh: " + std::to_string(node.mesh) + " out of range (there are " +
               std::to_string(model_.meshes.size()) + ")");
        for (int mesh : meshes_of(node.mesh)) scene_.instances.push_back({mesh, world});
      }
      stack.push_back({index, world, 0});
    };
    for (size_t r = 0; r < roots.size(); ++r) {
      enter(roots[r], glm::dmat4(1.0), roots_field + "[" + std::to_string(r) + "]");
      while (!stack.empty()) {
        Frame& top = stack.back();
        const std::vector<int>& children = model_.nodes[static_cast<size_t>(top.node)].children;
        if (top.next_child == children.size()) {
          on_path[static_cast<size_t>(top.node)] = 0;
          stack.pop_back();
          continue;
        }
        const size_t c = top.next_child++;
        const glm::dmat4 parent = top.world;  // enter() grows the stack, which may move `top`
        enter(children[c], parent, "nodes[" + std::to_string(top.node) + "].children[" + std::to_string(c) + "]");
      }
    }
  }

  // The Scene meshes of glTF mesh `index`, one per triangle primitive, converted once and shared by instances.
  const std::vector<int>& meshes_of(int index) {
    auto found = converted_.find(index);
    if (found != converted_.end()) return found->second;
    std::vector<int> ids;
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<size_t>(index)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const std::string where = "meshes[" + std::to_string(index) + "].primitives[" + std::to_string(p) + "]";
      const tinygltf::Primitive& primitive = mesh.primitives[p];
      if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
          primitive.mode != TINYGLTF_MODE_TRIANGLE_FAN && primitive.mode != -1) {
        report_.warnings.push_back(where + ": mode " + std::to_string(primitive.mode) + " is not triangles; skipped");
        continue;
      }
      Mesh converted = convert(primitive, where);
      if (converted.indices.empty()) continue;
      scene_.meshes.push_back(std::move(converted));
      ids.push_back(static_cast<int>(scene_.meshes.size()) - 1);
    }
    return converted_[index] = ids;
  }

  Mesh convert(const tinygltf::Primitive& primitive, const std::string& where) {
    const auto position_at = primitive.attributes.find("POSITION");
    if (position_at == primitive.attributes.end()) fail(where + ".attributes: POSITION is required");
    const auto positions = read_floats<3>(model_, position_at->second, where + ".attributes.POSITION",
                                          {TINYGLTF_COMPONENT_TYPE_FLOAT});
    const size_t vertex_count = positions.size();

    // glTF 2.0, 3.7.2.1: all attribute accessors of a primitive have the same count; checked for the
    // attributes the player does not read as well, as Khronos' validator does.
    for (const auto& [name, accessor] : primitive.attributes)
      if (accessor >= 0 && static_cast<size_t>(accessor) < model_.accessors.size() &&
          model_.accessors[static_cast<size_t>(accessor)].count != vertex_count)
        fail(where + ".attributes." + name + ": count " + std::to_string(model_.accessors[static_cast<size_t>(accessor)].count) +
             " differs from POSITION's " + std::to_string(vertex_count));

    std::vector<glm::vec3> normals;
    if (auto at = primitive.attributes.find("NORMAL"); at != primitive.attributes.end()) {
      normals = read_floats<3>(model_, at->second, where + ".attributes.NORMAL", {TINYGLTF_COMPONENT_TYPE_FLOAT});
      if (normals.size() != vertex_count) fail(where + ".attributes.NORMAL: count differs from POSITION's");
    }
    std::vector<glm::vec2> uvs;
    if (auto at = primitive.attributes.find("TEXCOORD_0"); at != primitive.attributes.end()) {
      uvs = read_floats<2>(model_, at->second, where + ".attributes.TEXCOORD_0",
                           {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                            TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT});
      if (uvs.size() != vertex_count) fail(where + ".attributes.TEXCOORD_0: count differs from POSITION's");
    }

    std::vector<uint32_t> indices;
    if (primitive.indices >= 0) {
      const View view = checked_view(model_, primitive.indices, where + ".indices",
                                     {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                      TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT}, 1);
      indices.resize(view.count);
      for (size_t i = 0; i < view.count; ++i) {
        const double value = component(view, i, 0);
        if (value >= static_cast<double>(vertex_count))
          fail(where + ".indices: element " + std::to_string(i) + " is " + std::to_string(static_cast<uint64_t>(value)) +
               ", expected less than the vertex count " + std::to_string(vertex_count));
        indices[i] = static_cast<uint32_t>(value);
      }
    } else {
      indices.resize(vertex_count);
      for (size_t i = 0; i < vertex_count; ++i) indices[i] = static_cast<uint32_t>(i);
    }
    indices = to_triangle_list(indices, primitive.mode);

    Mesh mesh;
    mesh.material = material(primitive.material, where);
    if (normals.empty()) {
      // The spec: without NORMAL, flat normals. Each triangle gets its own three vertices.
      mesh.vertices.reserve(indices.size());
      for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const glm::vec3 a = positions[indices[t]], b = positions[indices[t + 1]], c = positions[indices[t + 2]];
        const glm::dvec3 cross = glm::cross(glm::dvec3(b - a), glm::dvec3(c - a));
        const double length = glm::length(cross);
        const glm::vec3 normal = length > 0.0 && std::isfinite(length) ? glm::vec3(cross / length) : glm::vec3(0.0f);
        for (int k = 0; k < 3; ++k) {
          const uint32_t source = indices[t + static_cast<size_t>(k)];
          mesh.vertices.push_back({positions[source], normal, uvs.empty() ? glm::vec2(0.0f) : uvs[source]});
          mesh.indices.push_back(static_cast<uint32_t>(mesh.vertices.size() - 1));
        }
      }
    } else {
      mesh.vertices.resize(vertex_count);
      for (size_t i = 0; i < vertex_count; ++i) {
        const float length = glm::length(normals[i]);
        // Non-unit normals are normalised; zero ones stay zero and the shader faces them to the eye.
        const glm::vec3 normal = length > 1e-30f && std::isfinite(length) ? normals[i] / length : glm::vec3(0.0f);
        mesh.vertices[i] = {positions[i], normal, uvs.empty() ? glm::vec2(0.0f) : uvs[i]};
      }
      mesh.indices = std::move(indices);
    }
    mesh.min = glm::vec3(std::numeric_limits<float>::max());
    mesh.max = glm::vec3(std::numeric_limits<float>::lowest());
    for (const Vertex& v : mesh.vertices) {
      mesh.min = glm::min(mesh.min, v.position);
      mesh.max = glm::max(mesh.max, v.position);
    }
    return mesh;
  }

  static std::vector<uint32_t> to_triangle_list(const std::vector<uint32_t>& in, int mode) {
    std::vector<uint32_t> out;
    // glTF 2.0, 3.7.2.1: strip triangle i is {v_i, v_(i+1+i%2), v_(i+2-i%2)} (every other one flipped
    // back to counter-clockwise), fan triangle i is {v_(i+1), v_(i+2), v_0}; kept in exactly that order.
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (size_t i = 0; i + 2 < in.size(); ++i) out.insert(out.end(), {in[i], in[i + 1 + i % 2], in[i + 2 - i % 2]});
    } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
      for (size_t i = 0; i + 2 < in.size(); ++i) out.insert(out.end(), {in[i + 1], in[i + 2], in[0]});
    } else {
      out.assign(in.begin(), in.begin() + static_cast<std::ptrdiff_t>(in.size() / 3 * 3));
    }
    return out;
  }

  int material(int index, const std::string& where) {
    if (index < 0) return 0;
    if (static_cast<size_t>(index) >= model_.materials.size())
      fail(where + ".material: " + std::to_string(index) + " out of range (there are " +
           std::to_string(model_.materials.size()) + ")");
    if (auto found = materials_.find(index); found != materials_.end()) return found->second;
    const tinygltf::Material& source = model_.materials[static_cast<size_t>(index)];
    const std::string field = "materials[" + std::to_string(index) + "]";
    Material material;
    material.double_sided = source.doubleSided;
    const std::vector<double>& factor = source.pbrMetallicRoughness.baseColorFactor;
    if (factor.size() != 4) fail(field + ".pbrMetallicRoughness.baseColorFactor: expected 4 numbers");
    for (int c = 0; c < 4; ++c) {
      if (!std::isfinite(factor[static_cast<size_t>(c)]))
        fail(field + ".pbrMetallicRoughness.baseColorFactor: expected finite numbers");
      material.base_color[c] = static_cast<float>(std::clamp(factor[static_cast<size_t>(c)], 0.0, 1.0));
    }
    const tinygltf::TextureInfo& info = source.pbrMetallicRoughness.baseColorTexture;
    if (info.index >= 0) {
      if (info.texCoord != 0)
        report_.warnings.push_back(field + ".pbrMetallicRoughness.baseColorTexture.texCoord: only set 0 is used");
      material.base_color_texture = texture(info.index, field + ".pbrMetallicRoughness.baseColorTexture.index");
    }
    scene_.materials.push_back(material);
    return materials_[index] = static_cast<int>(scene_.materials.size()) - 1;
  }

  int texture(int index, const std::string& field) {
    if (static_cast<size_t>(index) >= model_.textures.size())
      fail(field + ": " + std::to_string(index) + " out of range (there are " + std::to_string(model_.textures.size()) + ")");
    if (auto found = textures_.find(index); found != textures_.end()) return found->second;
    const tinygltf::Texture& source = model_.textures[static_cast<size_t>(index)];
    const std::string where = "textures[" + std::to_string(index) + "]";
    if (source.source < 0 || static_cast<size_t>(source.source) >= model_.images.size())
      fail(where + ".source: " + std::to_string(source.source) + " is not an image index");
    const tinygltf::Image& image = model_.images[static_cast<size_t>(source.source)];
    // An image that could not be used is drawn white; load_gltf has put the reason in the warnings.
    if (image.image.empty()) return white_texture();
    const size_t expected = static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 4;
    if (image.width <= 0 || image.height <= 0 || image.component != 4 || image.bits != 8 || image.image.size() != expected)
      fail("images[" + std::to_string(source.source) + "]: expected decoded 8-bit RGBA pixels");
    Texture texture;
    texture.width = image.width;
    texture.height = image.height;
    texture.rgba = image.image;
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
    return textures_[index] = static_cast<int>(scene_.textures.size()) - 1;
  }

  int white_texture() {
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

  const tinygltf::Model& model_;
  LoadReport& report_;
  int white_ = -1;
  Scene scene_;
  std::map<int, std::vector<int>> converted_;
  std::map<int, int> materials_, textures_;
};

}  // namespace

bool load_gltf(const fs::path& file, Scene& out, LoadReport& report, const LoadOptions& options) {
  report = LoadReport{};
  const std::string name = file.string();
  auto refuse = [&](const std::string& problem) {
    report.error = name + ": " + problem;
    report.warnings.clear();
    return false;
  };
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return refuse("no such file");
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (extension != ".gltf" && extension != ".glb") return refuse("expected a .gltf or .glb file");
  const bool binary = extension == ".glb";

  std::string bytes;
  {
    std::ifstream in(file, std::ios::binary);
    if (!in) return refuse("cannot open the file");
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (bytes.empty()) return refuse("not a valid glTF 2.0 file: the file is empty (0 bytes); expected glTF 2.0 " + std::string(binary ? "binary" : "JSON"));
  Glb glb;
  if (binary) {
    // Layout and nesting problems keep the "not a valid glTF" of a parse error: the file is not
    // glTF at all, rather than glTF with one field wrong.
    if (const std::string problem = split_glb(bytes, glb, report.warnings); !problem.empty())
      return refuse("not a valid glTF 2.0 file: " + problem);
  } else {
    glb.json = std::move(bytes);
  }
  // The spec forbids a byte-order mark but lets readers ignore one, as most do (and tinygltf
  // would refuse it): ignored, with a warning so the exporter can be fixed.
  if (glb.json.compare(0, 3, "\xEF\xBB\xBF") == 0) {
    glb.json.erase(0, 3);
    report.warnings.push_back("the JSON starts with a UTF-8 byte-order mark, which glTF forbids; ignored");
  }
  if (const std::string problem = nesting_problem(glb.json); !problem.empty())
    return refuse("not a valid glTF 2.0 file: " + problem);
  json root;
  try {
    root = json::parse(glb.json);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number like 1e400
    std::string what = e.what();
    if (const size_t at = what.find("] "); at != std::string::npos) what.erase(0, at + 2);  // "[json.exception...] "
    return refuse("not a valid glTF 2.0 file: " + what);
  }
  if (const std::string problem = SchemaCheck(root, report.warnings).run(); !problem.empty()) return refuse(problem);
  if (const std::string problem = uri_problem(root); !problem.empty()) return refuse(problem);
  root = json();  // tinygltf parses its own copy; this one need not stay in memory beside it

  Confinement confinement{fs::weakly_canonical(fs::absolute(file)).parent_path()};
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({confined_exists, confined_expand, confined_read, refuse_write, &confinement});
  ImageContext images;
  images.options = &options;
  loader.SetImageLoader(load_image, &images);
  tinygltf::Model model;
  std::string error, warning;
  const std::string base_dir = fs::absolute(file).parent_path().string();
  bool parsed = false;
  if (binary) {
    const std::string joined = join_glb(glb);
    parsed = loader.LoadBinaryFromMemory(&model, &error, &warning, reinterpret_cast<const unsigned char*>(joined.data()),
                                         static_cast<unsigned int>(joined.size()), base_dir);
  } else {
    parsed = loader.LoadASCIIFromString(&model, &error, &warning, glb.json.data(), static_cast<unsigned int>(glb.json.size()),
                                        base_dir);
  }
  if (!parsed) {
    while (!error.empty() && (error.back() == '\n' || error.back() == ' ' || error.back() == ';')) error.pop_back();
    return refuse("not a valid glTF 2.0 file: " + (error.empty() ? "unknown parse error" : error));
  }
  // Images tinygltf could not read (a missing external file) reach no decoder; they too are white.
  for (size_t i = 0; i < model.images.size(); ++i) {
    const int index = static_cast<int>(i);
    if (model.images[i].image.empty() && !images.problems.count(index))
      images.problems[index] = "'" + model.images[i].uri + "' cannot be read";
  }
  for (const auto& [index, problem] : images.problems)
    report.warnings.push_back("images[" + std::to_string(index) + "]: " + problem + "; its texture is drawn white");
  try {
    Builder builder(model, report);
    out = builder.build(fs::path(file).filename().string());
  } catch (const LoadError& e) {
    return refuse(e.message);
  }
  return true;
}

}  // namespace scene
