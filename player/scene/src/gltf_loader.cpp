#include "scene/gltf_loader.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cmath>
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
constexpr int kMaxImageSide = 16384;

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

// The JSON part of a .gltf or .glb, read only to check URIs before tinygltf follows them.
nlohmann::json json_of(const fs::path& file, bool binary) {
  std::ifstream in(file, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (binary) {
    // 12-byte header, then the first chunk: length, type "JSON", data.
    if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0 || bytes.compare(16, 4, "JSON") != 0) return {};
    uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    if (length > bytes.size() - 20) return {};
    bytes = bytes.substr(20, length);
  }
  return nlohmann::json::parse(bytes, nullptr, false);
}

// External files may only be named relative to the scene's folder and may not climb out of it.
std::string uri_problem(const nlohmann::json& json) {
  for (const char* array : {"buffers", "images"}) {
    const auto found = json.find(array);
    if (found == json.end() || !found->is_array()) continue;
    for (size_t i = 0; i < found->size(); ++i) {
      const nlohmann::json& entry = (*found)[i];
      if (!entry.is_object() || !entry.contains("uri") || !entry["uri"].is_string()) continue;
      const std::string uri = entry["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0) continue;
      const std::string field = std::string(array) + "[" + std::to_string(i) + "].uri";
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

// --- Images through OpenImageIO ------------------------------------------------------------------

bool load_image(tinygltf::Image* image, const int index, std::string* err, std::string*, int, int,
                const unsigned char* bytes, int size, void*) {
  auto complain = [&](const std::string& what) {
    if (err) *err += "images[" + std::to_string(index) + "]: " + what + "; ";
    return false;
  };
  if (size < 4) return complain("image data is empty or truncated");
  // OpenImageIO picks the reader by file extension; glTF images are PNG or JPEG by magic number.
  const char* kind = bytes[0] == 0x89 && bytes[1] == 'P' ? "image.png" : bytes[0] == 0xFF && bytes[1] == 0xD8 ? "image.jpg" : nullptr;
  if (!kind) return complain("expected PNG or JPEG data");
  OIIO::Filesystem::IOMemReader memory(const_cast<unsigned char*>(bytes), static_cast<size_t>(size));
  auto input = OIIO::ImageInput::open(kind, nullptr, &memory);
  if (!input) return complain("cannot decode: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.width > kMaxImageSide || spec.height > kMaxImageSide)
    return complain("size " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " outside 1.." +
                    std::to_string(kMaxImageSide));
  std::vector<unsigned char> pixels(static_cast<size_t>(spec.width) * static_cast<size_t>(spec.height) * 4, 255);
  const int channels = std::min(spec.nchannels, 4);
  if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data(), 4))
    return complain("cannot decode: " + input->geterror());
  if (channels < 3) {  // grey (+ alpha): spread grey over RGB
    for (size_t p = 0; p < pixels.size(); p += 4) {
      if (channels == 2) pixels[p + 3] = pixels[p + 1];
      pixels[p + 1] = pixels[p + 2] = pixels[p];
    }
  }
  image->width = spec.width;
  image->height = spec.height;
  image->component = 4;
  image->bits = 8;
  image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  image->image = std::move(pixels);
  return true;
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
  if (std::find(types.begin(), types.end(), accessor.componentType) == types.end())
    fail(where + ": componentType " + std::to_string(accessor.componentType) + " is not allowed here");
  const int actual_components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(accessor.type));
  if (actual_components != components)
    fail(where + ": expected " + std::to_string(components) + " components per element, got " +
         std::to_string(actual_components));
  if (accessor.count == 0) fail(where + ": count is 0");
  if (accessor.count > kMaxElements) fail(where + ": count " + std::to_string(accessor.count) + " exceeds the limit");
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
  if (view.stride < element) fail(where + ": byteStride " + std::to_string(view.stride) + " is smaller than an element");
  const size_t span = accessor.byteOffset + view.stride * (accessor.count - 1) + element;
  if (accessor.byteOffset > buffer_view.byteLength || span > buffer_view.byteLength)
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
    if (!model_.scenes.empty()) {
      const int index = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (static_cast<size_t>(index) >= model_.scenes.size())
        fail("scene: " + std::to_string(index) + " out of range (there are " + std::to_string(model_.scenes.size()) + ")");
      shown = &model_.scenes[static_cast<size_t>(index)];
    }
    if (!shown || shown->nodes.empty()) fail("scenes: the file has no scene with nodes to show");
    std::vector<int> path;
    for (size_t i = 0; i < shown->nodes.size(); ++i)
      visit(shown->nodes[i], glm::dmat4(1.0), "scenes[].nodes[" + std::to_string(i) + "]", path);
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

  void visit(int index, const glm::dmat4& parent, const std::string& field, std::vector<int>& path) {
    if (index < 0 || static_cast<size_t>(index) >= model_.nodes.size())
      fail(field + ": node index " + std::to_string(index) + " out of range (there are " +
           std::to_string(model_.nodes.size()) + ")");
    if (std::find(path.begin(), path.end(), index) != path.end())
      fail("nodes[" + std::to_string(index) + "].children: the node hierarchy has a cycle through this node");
    if (!visited_.insert(index).second)
      fail("nodes[" + std::to_string(index) + "]: the node has more than one parent (glTF requires a tree)");
    const std::string where = "nodes[" + std::to_string(index) + "]";
    const tinygltf::Node& node = model_.nodes[static_cast<size_t>(index)];
    const glm::dmat4 world = parent * local_transform(node, where);
    if (node.mesh >= 0) {
      if (static_cast<size_t>(node.mesh) >= model_.meshes.size())
        fail(where + ".mesh: " + std::to_string(node.mesh) + " out of range (there are " +
             std::to_string(model_.meshes.size()) + ")");
      for (int mesh : meshes_of(node.mesh)) scene_.instances.push_back({mesh, world});
    }
    path.push_back(index);
    for (size_t c = 0; c < node.children.size(); ++c)
      visit(node.children[c], world, where + ".children[" + std::to_string(c) + "]", path);
    path.pop_back();
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
      texture.mipmaps = sampler.minFilter < 0 || sampler.minFilter >= TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST;
      texture.repeat_s = sampler.wrapS != TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
      texture.repeat_t = sampler.wrapT != TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
    } else if (source.sampler >= 0) {
      fail(where + ".sampler: " + std::to_string(source.sampler) + " out of range");
    }
    scene_.textures.push_back(std::move(texture));
    return textures_[index] = static_cast<int>(scene_.textures.size()) - 1;
  }

  const tinygltf::Model& model_;
  LoadReport& report_;
  Scene scene_;
  std::set<int> visited_;
  std::map<int, std::vector<int>> converted_;
  std::map<int, int> materials_, textures_;
};

}  // namespace

bool load_gltf(const fs::path& file, Scene& out, LoadReport& report) {
  report = LoadReport{};
  const std::string name = file.string();
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    report.error = name + ": no such file";
    return false;
  }
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (extension != ".gltf" && extension != ".glb") {
    report.error = name + ": expected a .gltf or .glb file";
    return false;
  }
  if (const std::string problem = uri_problem(json_of(file, extension == ".glb")); !problem.empty()) {
    report.error = name + ": " + problem;
    return false;
  }
  Confinement confinement{fs::weakly_canonical(fs::absolute(file)).parent_path()};
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({confined_exists, confined_expand, confined_read, refuse_write, &confinement});
  loader.SetImageLoader(load_image, nullptr);
  tinygltf::Model model;
  std::string error, warning;
  const std::string path = fs::absolute(file).string();
  const bool parsed = extension == ".glb" ? loader.LoadBinaryFromFile(&model, &error, &warning, path)
                                          : loader.LoadASCIIFromFile(&model, &error, &warning, path);
  if (!parsed) {
    while (!error.empty() && (error.back() == '\n' || error.back() == ' ' || error.back() == ';')) error.pop_back();
    report.error = name + ": not a valid glTF 2.0 file: " + (error.empty() ? "unknown parse error" : error);
    return false;
  }
  try {
    Builder builder(model, report);
    out = builder.build(fs::path(file).filename().string());
  } catch (const LoadError& e) {
    report.error = name + ": " + e.message;
    return false;
  }
  return true;
}

}  // namespace scene
