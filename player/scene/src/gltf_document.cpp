#include "gltf_document.h"

#include "gltf_accessors.h"
#include "gltf_images.h"
#include "gltf_meshopt.h"

#include <algorithm>

namespace scene::gltf {
using nlohmann::json;

namespace {

// tinygltf never touches the file system: the document reads every byte itself. These answer
// tinygltf's callbacks should it ever try.
bool no_file(const std::string&, void*) {
  return false;
}
std::string same_path(const std::string& path, void*) {
  return path;
}
bool no_read(std::vector<unsigned char>*, std::string* err, const std::string& path, void*) {
  if (err) *err += "'" + path + "': the loader reads a scene's files itself; ";
  return false;
}
bool no_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "the loader never writes files; ";
  return false;
}
bool no_image(tinygltf::Image*, int, std::string* err, std::string*, int, int, const unsigned char*, int, void*) {
  if (err) *err += "the loader decodes a scene's images itself; ";
  return false;
}

const json* find(const json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  const auto found = object.find(key);
  return found == object.end() ? nullptr : &*found;
}

// Element `index` of the top-level array `array`, or null when there is none.
const json* entry(const json& root, const char* array, int index) {
  const json* values = find(root, array);
  if (!values || !values->is_array() || index < 0 || static_cast<size_t>(index) >= values->size()) return nullptr;
  return &(*values)[static_cast<size_t>(index)];
}

}  // namespace

Document::Document(json root, Glb glb, std::filesystem::path folder, const LoadOptions& options,
                   std::vector<std::string>& warnings)
    : root_(std::move(root)), glb_(std::move(glb)), folder_(std::move(folder)), options_(options), warnings_(warnings) {}

std::string Document::parse() {
  // tinygltf reads the structure from a copy without the byte sources (buffers and images are
  // read here, when used), with indices taken out of primitives (tinygltf refuses an index
  // accessor without a buffer view, which glTF allows: zeros, or a Draco-compressed primitive) and
  // accessor types it does not know replaced (glTF-Validator warns; the accessor is refused if read).
  // The schema check has established that these are arrays of objects.
  json copy = root_;
  copy.erase("buffers");
  copy.erase("images");
  if (copy.contains("meshes"))
    for (json& mesh : copy["meshes"])
      if (mesh.contains("primitives"))
        for (json& primitive : mesh["primitives"]) primitive.erase("indices");
  if (copy.contains("accessors"))
    for (json& accessor : copy["accessors"])
      if (!known_accessor_type(accessor.value("type", std::string()))) accessor["type"] = "SCALAR";
  const std::string text = copy.dump();
  copy = json();

  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({no_file, same_path, no_read, no_write, nullptr});
  loader.SetImageLoader(no_image, nullptr);
  std::string error, warning;
  if (!loader.LoadASCIIFromString(&model_, &error, &warning, text.data(), static_cast<unsigned int>(text.size()), ""))
    return error.empty() ? "unknown parse error" : error;
  const json* meshes = find(root_, "meshes");
  for (size_t m = 0; meshes && m < meshes->size() && m < model_.meshes.size(); ++m) {
    const json* primitives = find((*meshes)[m], "primitives");
    for (size_t p = 0; primitives && p < primitives->size() && p < model_.meshes[m].primitives.size(); ++p)
      if (const json* indices = find((*primitives)[p], "indices")) model_.meshes[m].primitives[p].indices = indices->get<int>();
  }
  return {};
}

bool Document::uses_extension(const std::string& name) const {
  const json* used = find(root_, "extensionsUsed");
  if (!used || !used->is_array()) return false;
  return std::find(used->begin(), used->end(), name) != used->end();
}

std::vector<unsigned char> Document::read_uri(const std::string& uri, const std::string& field, size_t expected_bytes) {
  std::vector<unsigned char> bytes;
  std::string problem;
  if (uri.rfind("data:", 0) == 0) {
    if (!decode_data_uri(uri, bytes, problem)) fail(field + ": " + problem);
  } else {
    if (const std::string confined = uri_problem(uri); !confined.empty()) fail(field + ": " + confined);
    if (!read_confined(folder_, uri, bytes, problem)) fail(field + ": " + problem);
  }
  if (expected_bytes && bytes.size() < expected_bytes)
    fail(field + ": " + std::to_string(bytes.size()) + " bytes; expected byteLength " + std::to_string(expected_bytes));
  return bytes;
}

const std::vector<unsigned char>& Document::buffer(int index, const std::string& field) {
  if (auto found = buffers_.find(index); found != buffers_.end()) return found->second;
  const std::string where = field + " -> buffers[" + std::to_string(index) + "]";
  const json* found_source = entry(root_, "buffers", index);
  if (!found_source) fail(where + ": out of range");
  const json& source = *found_source;
  const size_t byte_length = source.value("byteLength", size_t{0});
  std::vector<unsigned char> bytes;
  if (const json* uri = find(source, "uri"); uri && uri->is_string()) {
    bytes = read_uri(uri->get<std::string>(), where + ".uri", byte_length);
  } else if (index == 0 && glb_.has_bin) {
    // glTF 2.0, 4.4.3.3: the BIN chunk may be up to 3 bytes longer than the buffer (padding).
    if (glb_.bin.size() < byte_length)
      fail(where + ".byteLength: " + std::to_string(byte_length) + " bytes, but the GLB's BIN chunk has " +
           std::to_string(glb_.bin.size()));
    bytes.assign(glb_.bin.begin(), glb_.bin.begin() + static_cast<std::ptrdiff_t>(byte_length));
  } else if (const json* extensions = find(source, "extensions"); extensions && find(*extensions, "EXT_meshopt_compression")) {
    fail(where + ": a meshopt fallback buffer without data; expected it to be read only through EXT_meshopt_compression");
  } else {
    fail(where + ": has no uri" + std::string(index == 0 ? " and the file has no BIN chunk" : "") +
         "; expected a uri (only buffers[0] of a .glb may use the BIN chunk)");
  }
  bytes.resize(byte_length);  // a file longer than byteLength: the rest is not part of the buffer
  return buffers_[index] = std::move(bytes);
}

Bytes Document::view_bytes(int index, const std::string& field) {
  const std::string where = field + " -> bufferViews[" + std::to_string(index) + "]";
  if (index < 0 || static_cast<size_t>(index) >= model_.bufferViews.size()) fail(where + ": out of range");
  const tinygltf::BufferView& view = model_.bufferViews[static_cast<size_t>(index)];
  if (auto found = decoded_views_.find(index); found != decoded_views_.end()) return {found->second.data(), found->second.size()};
  const json* source = entry(root_, "bufferViews", index);
  if (const json* extensions = source ? find(*source, "extensions") : nullptr)
    if (const json* meshopt = find(*extensions, "EXT_meshopt_compression")) {
      const MeshoptView request = meshopt_view(*meshopt, view.byteLength, view.byteStride, where);
      const std::vector<unsigned char>& data = buffer(request.buffer, where + ".extensions.EXT_meshopt_compression.buffer");
      if (request.byte_offset > data.size() || request.byte_length > data.size() - request.byte_offset)
        fail(where + ".extensions.EXT_meshopt_compression: bytes " + std::to_string(request.byte_offset) + ".." +
             std::to_string(request.byte_offset + request.byte_length) + " lie beyond its buffer of " +
             std::to_string(data.size()) + " bytes");
      charge(view.byteLength, where + ".extensions.EXT_meshopt_compression");
      std::vector<unsigned char> decoded = decode_meshopt(request, data.data() + request.byte_offset, view.byteLength, where);
      auto& stored = decoded_views_[index] = std::move(decoded);
      return {stored.data(), stored.size()};
    }
  const std::vector<unsigned char>& data = buffer(view.buffer, where + ".buffer");
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
    fail(where + ": bytes " + std::to_string(view.byteOffset) + ".." + std::to_string(view.byteOffset + view.byteLength) +
         " lie beyond buffers[" + std::to_string(view.buffer) + "] of " + std::to_string(data.size()) + " bytes");
  return {data.data() + view.byteOffset, view.byteLength};
}

void Document::charge(size_t bytes, const std::string& field) {
  if (bytes > options_.decoded_budget_bytes - decoded_bytes_)
    fail(field + ": decoding it would bring the scene to " + std::to_string(decoded_bytes_ + bytes) +
         " bytes of decoded data; the limit is " + std::to_string(options_.decoded_budget_bytes) + " bytes");
  decoded_bytes_ += bytes;
}

const DecodedImage& Document::image(int index, const std::string& field) {
  if (auto found = images_.find(index); found != images_.end()) return found->second;
  const std::string where = "images[" + std::to_string(index) + "]";
  const json* found_source = entry(root_, "images", index);
  if (!found_source) fail(field + ": image " + std::to_string(index) + " out of range");
  const json& source = *found_source;
  DecodedImage decoded;
  std::string problem;
  try {
    std::vector<unsigned char> owned;
    Bytes bytes;
    if (const json* uri = find(source, "uri"); uri && uri->is_string()) {
      owned = read_uri(uri->get<std::string>(), where + ".uri", 0);
      bytes = {owned.data(), owned.size()};
    } else if (const json* view = find(source, "bufferView"); view && view->is_number_integer()) {
      bytes = view_bytes(view->get<int>(), where + ".bufferView");
    } else {
      fail(where + ": expected a uri or a bufferView");
    }
    LoadOptions within_budget = options_;
    within_budget.image_budget_bytes = std::min(options_.image_budget_bytes, options_.decoded_budget_bytes - decoded_bytes_);
    decoded = decode_image(bytes.data, bytes.size, within_budget, problem);
    if (problem.empty()) charge(decoded.rgba.size(), where);
  } catch (const LoadError& e) {
    // A missing or unreadable image file does not stop the scene; the texture is drawn white.
    problem = e.message;
  }
  if (!problem.empty()) {
    decoded = DecodedImage{};
    warnings_.push_back(where + ": " + problem + "; its texture is drawn white");
  }
  return images_[index] = std::move(decoded);
}

}  // namespace scene::gltf
