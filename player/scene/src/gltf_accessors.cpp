#include "gltf_accessors.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace scene::gltf {

size_t component_size(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return 4;
    default:
      return 0;
  }
}

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
         " of its buffer; expected a multiple of the component size " + std::to_string(component_size(accessor.componentType)));
  // count <= kMaxElements and stride <= 252 (schema-checked) keep the product far from overflow;
  // the offset is compared first so the sum cannot wrap either.
  if (accessor.byteOffset > buffer_view.byteLength)
    fail(where + ": byteOffset " + std::to_string(accessor.byteOffset) + " lies beyond its buffer view of " +
         std::to_string(buffer_view.byteLength) + " bytes");
  const size_t span = accessor.byteOffset + view.stride * (accessor.count - 1) + element;
  if (span > buffer_view.byteLength)
    fail(where + ": needs " + std::to_string(span) + " bytes but its buffer view has " + std::to_string(buffer_view.byteLength));
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
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      return read(float{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      return view.normalized ? read(uint8_t{}) / 255.0 : read(uint8_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      return view.normalized ? read(uint16_t{}) / 65535.0 : read(uint16_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      return read(uint32_t{});
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      return view.normalized ? std::max(read(int8_t{}) / 127.0, -1.0) : read(int8_t{});
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      return view.normalized ? std::max(read(int16_t{}) / 32767.0, -1.0) : read(int16_t{});
    default:
      return 0.0;
  }
}

}  // namespace scene::gltf
