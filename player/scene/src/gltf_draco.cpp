#include "gltf_draco.h"

#include "gltf_accessors.h"

#include <draco/compression/decode.h>

#include <new>

namespace scene::gltf {
using nlohmann::json;

DracoPrimitive decode_draco(Document& document, const json& extension, const std::map<std::string, int>& attributes,
                            int indices_accessor, const std::string& where) {
  const std::string at = where + ".extensions.KHR_draco_mesh_compression";
  if (!extension.is_object()) fail(at + ": expected an object");
  const auto view = extension.find("bufferView");
  if (view == extension.end() || !view->is_number_unsigned())
    fail(at + ".bufferView: missing or not an index; expected the buffer view holding the compressed mesh");
  const auto mapping = extension.find("attributes");
  if (mapping == extension.end() || !mapping->is_object())
    fail(at + ".attributes: missing; expected an object naming each compressed attribute's Draco id");
  if (view->get<uint64_t>() > static_cast<uint64_t>(INT32_MAX)) fail(at + ".bufferView: out of range");
  const Bytes bytes = document.view_bytes(view->get<int>(), at + ".bufferView");

  draco::DecoderBuffer buffer;
  buffer.Init(reinterpret_cast<const char*>(bytes.data), bytes.size);
  draco::Decoder decoder;
  std::unique_ptr<draco::Mesh> mesh;
  try {
    auto decoded = decoder.DecodeMeshFromBuffer(&buffer);
    if (!decoded.ok()) fail(at + ": the compressed mesh cannot be decoded (" + decoded.status().error_msg_string() + ")");
    mesh = std::move(decoded).value();
  } catch (const std::bad_alloc&) {
    fail(at + ": the compressed mesh asks for more memory than there is (a corrupt header)");
  } catch (const std::length_error&) {
    fail(at + ": the compressed mesh asks for more memory than there is (a corrupt header)");
  }
  if (!mesh) fail(at + ": the compressed data holds no mesh");

  DracoPrimitive out;
  out.points = mesh->num_points();
  if (out.points == 0 || out.points > kMaxElements)
    fail(at + ": the decoded mesh has " + std::to_string(out.points) + " points; expected 1.." + std::to_string(kMaxElements));
  const tinygltf::Model& model = document.model();
  for (const auto& [name, id] : mapping->items()) {
    const std::string field = at + ".attributes." + name;
    if (!id.is_number_unsigned() || id.get<uint64_t>() > static_cast<uint64_t>(INT32_MAX))
      fail(field + ": " + id.dump() + " is not a Draco attribute id");
    const auto accessor_at = attributes.find(name);
    if (accessor_at == attributes.end())
      fail(field + ": the primitive has no attribute " + name + "; expected every compressed attribute to be listed there");
    const draco::PointAttribute* attribute = mesh->GetAttributeByUniqueId(static_cast<uint32_t>(id.get<uint64_t>()));
    if (!attribute) fail(field + ": the decoded mesh has no attribute with id " + id.dump());
    const tinygltf::Accessor& accessor = model.accessors.at(static_cast<size_t>(accessor_at->second));
    const int components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(accessor.type));
    if (components <= 0 || components > 4 || attribute->num_components() != components)
      fail(field + ": the decoded attribute has " + std::to_string(attribute->num_components()) +
           " components; its accessor declares " + std::to_string(components));
    if (accessor.count != out.points)
      fail(field + ": accessors[" + std::to_string(accessor_at->second) + "].count " + std::to_string(accessor.count) +
           " differs from the decoded mesh's " + std::to_string(out.points) + " points");
    std::vector<float>& values = out.attributes[name];
    values.resize(out.points * static_cast<size_t>(components));
    for (size_t p = 0; p < out.points; ++p) {
      const draco::AttributeValueIndex value = attribute->mapped_index(draco::PointIndex(static_cast<uint32_t>(p)));
      if (!attribute->ConvertValue<float>(value, static_cast<int8_t>(components), &values[p * static_cast<size_t>(components)]))
        fail(field + ": point " + std::to_string(p) + " cannot be converted to numbers");
    }
    out.components[name] = components;
  }
  out.indices.reserve(mesh->num_faces() * 3);
  for (draco::FaceIndex f(0); f < mesh->num_faces(); ++f)
    for (const draco::PointIndex& point : mesh->face(f)) {
      if (point.value() >= out.points) fail(at + ": face " + std::to_string(f.value()) + " names a point beyond the mesh");
      out.indices.push_back(point.value());
    }
  if (indices_accessor >= 0) {
    const tinygltf::Accessor& accessor = model.accessors.at(static_cast<size_t>(indices_accessor));
    if (accessor.count != out.indices.size())
      fail(where + ".indices: accessors[" + std::to_string(indices_accessor) + "].count " + std::to_string(accessor.count) +
           " differs from the decoded mesh's " + std::to_string(out.indices.size()) + " indices");
  }
  return out;
}

}  // namespace scene::gltf
