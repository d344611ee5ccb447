#include "gltf_accessors.h"

#include "gltf_document.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace scene::gltf {
namespace {

std::string format_name(const Format& format) {
  std::string name;
  switch (format.component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
      name = "signed byte";
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
      name = "unsigned byte";
      break;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
      name = "signed short";
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
      name = "unsigned short";
      break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
      name = "unsigned int";
      break;
    case TINYGLTF_COMPONENT_TYPE_FLOAT:
      name = "float";
      break;
    default:
      name = "componentType " + std::to_string(format.component_type);
  }
  return format.normalized ? name + " normalized" : name;
}

// `count` elements of `components` components of `component_type`, `stride` bytes apart from byte
// `offset` of buffer view `buffer_view`; every byte checked to lie inside the view.
View span_view(Document& document, int buffer_view, size_t offset, size_t count, int component_type, int components,
               bool normalized, bool strided, const std::string& where) {
  const tinygltf::Model& model = document.model();
  if (buffer_view < 0 || static_cast<size_t>(buffer_view) >= model.bufferViews.size())
    fail(where + ": bufferView " + std::to_string(buffer_view) + " out of range");
  const tinygltf::BufferView& source = model.bufferViews[static_cast<size_t>(buffer_view)];
  const std::string view_name = "bufferViews[" + std::to_string(buffer_view) + "]";
  View view;
  view.count = count;
  view.component_type = component_type;
  view.components = components;
  view.normalized = normalized;
  const size_t element = component_size(component_type) * static_cast<size_t>(components);
  view.stride = strided && source.byteStride != 0 ? source.byteStride : element;
  if (view.stride < element)
    fail(where + ": " + view_name + ".byteStride " + std::to_string(view.stride) + " is smaller than an element of " +
         std::to_string(element) + " bytes");
  // glTF 2.0, 3.6.2.4: every component starts at a multiple of its size.
  if ((source.byteOffset + offset) % component_size(component_type) != 0)
    fail(where + ": starts at byte " + std::to_string(source.byteOffset + offset) +
         " of its buffer; expected a multiple of the component size " + std::to_string(component_size(component_type)));
  // count <= kMaxElements and stride <= 252 (schema-checked) keep the product far from overflow;
  // the offset is compared first so the sum cannot wrap either.
  if (offset > source.byteLength)
    fail(where + ": byteOffset " + std::to_string(offset) + " lies beyond its buffer view of " +
         std::to_string(source.byteLength) + " bytes");
  const size_t span = offset + view.stride * (count - 1) + element;
  if (span > source.byteLength)
    fail(where + ": needs " + std::to_string(span) + " bytes but its buffer view has " + std::to_string(source.byteLength));
  const Bytes bytes = document.view_bytes(buffer_view, where);
  view.data = bytes.data + offset;
  return view;
}

}  // namespace

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

bool known_accessor_type(const std::string& type) {
  for (const char* known : {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"})
    if (type == known) return true;
  return false;
}

void read_accessor(Document& document, int index, const std::string& field, const std::vector<Format>& formats, int components,
                   const std::function<void(size_t)>& begin, const std::function<void(size_t, const double*)>& element) {
  const tinygltf::Model& model = document.model();
  if (index < 0 || static_cast<size_t>(index) >= model.accessors.size())
    fail(field + ": accessor index " + std::to_string(index) + " out of range (there are " +
         std::to_string(model.accessors.size()) + ")");
  const tinygltf::Accessor& accessor = model.accessors[static_cast<size_t>(index)];
  const std::string where = field + " (accessors[" + std::to_string(index) + "])";
  const auto& root_accessor = document.root().at("accessors").at(static_cast<size_t>(index));
  if (const std::string type = root_accessor.value("type", std::string()); !known_accessor_type(type))
    fail(where + ".type: \"" + type + "\" is not a glTF accessor type; expected SCALAR, VEC2, VEC3, VEC4, MAT2, MAT3 or MAT4");
  const bool allowed = std::any_of(formats.begin(), formats.end(), [&](const Format& format) {
    return format.component_type == accessor.componentType && format.normalized == accessor.normalized;
  });
  if (!allowed) {
    std::string list;
    for (const Format& format : formats) list += (list.empty() ? "" : ", ") + format_name(format);
    fail(where + ": " + format_name({accessor.componentType, accessor.normalized}) + " is not allowed here; expected " +
         (formats.size() == 1 ? "" : "one of ") + list);
  }
  const int actual_components = tinygltf::GetNumComponentsInType(static_cast<uint32_t>(accessor.type));
  if (actual_components != components)
    fail(where + ": expected " + std::to_string(components) + " components per element, got " +
         std::to_string(actual_components));
  if (accessor.count == 0) fail(where + ": count is 0");
  if (accessor.count > kMaxElements)
    fail(where + ": count " + std::to_string(accessor.count) + " exceeds the limit of " + std::to_string(kMaxElements) +
         " elements");
  View dense;
  dense.count = accessor.count;
  dense.component_type = accessor.componentType;
  dense.components = components;
  dense.normalized = accessor.normalized;
  if (accessor.bufferView >= 0)  // glTF 2.0, 3.6.2.3: without a buffer view, all zeros
    dense = span_view(document, accessor.bufferView, accessor.byteOffset, accessor.count, accessor.componentType, components,
                      accessor.normalized, true, where);
  // What the caller keeps: one float (or index) per component.
  document.charge(accessor.count * static_cast<size_t>(components) * sizeof(float), where);
  begin(accessor.count);
  double values[16];
  for (size_t i = 0; i < dense.count; ++i) {
    for (int c = 0; c < components; ++c) values[c] = component(dense, i, c);
    element(i, values);
  }
  if (!accessor.sparse.isSparse) return;

  // glTF 2.0, 3.6.2.3: `count` indices, strictly increasing and below the accessor's count, and as
  // many values, tightly packed in their buffer views.
  const auto& sparse = accessor.sparse;
  const std::string sparse_where = where + ".sparse";
  if (sparse.count <= 0 || static_cast<size_t>(sparse.count) > accessor.count)
    fail(sparse_where + ".count: " + std::to_string(sparse.count) + "; expected 1.." + std::to_string(accessor.count));
  const size_t count = static_cast<size_t>(sparse.count);
  const int index_type = sparse.indices.componentType;
  if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail(sparse_where + ".indices.componentType: " + std::to_string(index_type) + "; expected 5121, 5123 or 5125");
  const View indices = span_view(document, sparse.indices.bufferView, static_cast<size_t>(sparse.indices.byteOffset), count,
                                 index_type, 1, false, false, sparse_where + ".indices");
  const View substitutes = span_view(document, sparse.values.bufferView, static_cast<size_t>(sparse.values.byteOffset), count,
                                     accessor.componentType, components, accessor.normalized, false, sparse_where + ".values");
  double previous = -1.0;
  for (size_t k = 0; k < count; ++k) {
    const double target = component(indices, k, 0);
    if (target <= previous || target >= static_cast<double>(accessor.count))
      fail(sparse_where + ".indices: element " + std::to_string(k) + " is " + std::to_string(static_cast<uint64_t>(target)) +
           "; expected strictly increasing indices below the accessor's count " + std::to_string(accessor.count));
    previous = target;
    for (int c = 0; c < components; ++c) values[c] = component(substitutes, k, c);
    element(static_cast<size_t>(target), values);
  }
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
