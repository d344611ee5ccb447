#include "gltf_meshopt.h"

#include "gltf_accessors.h"
#include "gltf_bytes.h"

#include <meshoptimizer.h>
#include <nlohmann/json.hpp>

namespace scene::gltf {
using nlohmann::json;
namespace {

// The vertex codec spends at least two bits on 16 bytes of a byte channel (a group of zeros), so
// its output is at most 64 times its input; the index codecs expand less. A request beyond that is
// a lie about the data, refused before the decoded view is allocated.
constexpr size_t kMaxExpansion = 64;
constexpr size_t kCodecSlack = 4096;  // block headers and the tail of a short stream

size_t unsigned_field(const json& object, const char* key, const std::string& where, bool required, size_t fallback = 0) {
  const auto found = object.find(key);
  if (found == object.end()) {
    if (required) fail(where + "." + key + ": missing; expected a non-negative integer");
    return fallback;
  }
  if (!found->is_number_unsigned()) fail(where + "." + key + ": " + found->dump() + " is not a non-negative integer");
  return found->get<size_t>();
}

}  // namespace

MeshoptView meshopt_view(const json& extension, size_t view_length, size_t view_stride, const std::string& where) {
  const std::string at = where + ".extensions.EXT_meshopt_compression";
  if (!extension.is_object()) fail(at + ": expected an object");
  MeshoptView view;
  const size_t buffer = unsigned_field(extension, "buffer", at, true);
  if (buffer > 1u << 30) fail(at + ".buffer: " + std::to_string(buffer) + " out of range");
  view.buffer = static_cast<int>(buffer);
  view.byte_offset = unsigned_field(extension, "byteOffset", at, false);
  view.byte_length = unsigned_field(extension, "byteLength", at, true);
  view.byte_stride = unsigned_field(extension, "byteStride", at, true);
  view.count = unsigned_field(extension, "count", at, true);
  auto text = [&](const char* key, const char* fallback) {
    const auto found = extension.find(key);
    if (found == extension.end()) return std::string(fallback);
    return found->is_string() ? found->get<std::string>() : std::string();  // not a string: no name matches
  };
  const std::string mode = text("mode", "");
  if (mode == "ATTRIBUTES")
    view.mode = MeshoptMode::attributes;
  else if (mode == "TRIANGLES")
    view.mode = MeshoptMode::triangles;
  else if (mode == "INDICES")
    view.mode = MeshoptMode::indices;
  else
    fail(at + ".mode: " + (extension.contains("mode") ? extension["mode"].dump() : std::string("missing")) +
         "; expected \"ATTRIBUTES\", \"TRIANGLES\" or \"INDICES\"");
  const std::string filter = text("filter", "NONE");
  if (filter == "NONE")
    view.filter = MeshoptFilter::none;
  else if (filter == "OCTAHEDRAL")
    view.filter = MeshoptFilter::octahedral;
  else if (filter == "QUATERNION")
    view.filter = MeshoptFilter::quaternion;
  else if (filter == "EXPONENTIAL")
    view.filter = MeshoptFilter::exponential;
  else
    fail(at + ".filter: " + extension["filter"].dump() +
         "; expected \"NONE\", \"OCTAHEDRAL\", \"QUATERNION\" or \"EXPONENTIAL\"");

  const size_t stride = view.byte_stride;
  if (view.mode == MeshoptMode::attributes) {
    if (stride == 0 || stride % 4 != 0 || stride > 256)
      fail(at + ".byteStride: " + std::to_string(stride) + "; expected a multiple of 4 from 4 to 256 for ATTRIBUTES");
    if (view_stride != 0 && view_stride != stride)
      fail(at + ".byteStride: " + std::to_string(stride) + " differs from the buffer view's byteStride " +
           std::to_string(view_stride));
  } else {
    if (stride != 2 && stride != 4) fail(at + ".byteStride: " + std::to_string(stride) + "; expected 2 or 4 for " + mode);
    if (view.filter != MeshoptFilter::none) fail(at + ".filter: " + filter + "; expected NONE for " + mode);
    if (view.mode == MeshoptMode::triangles && view.count % 3 != 0)
      fail(at + ".count: " + std::to_string(view.count) + "; expected a multiple of 3 for TRIANGLES");
  }
  if ((view.filter == MeshoptFilter::octahedral && stride != 4 && stride != 8) ||
      (view.filter == MeshoptFilter::quaternion && stride != 8))
    fail(at + ".byteStride: " + std::to_string(stride) + " does not suit the " + filter + " filter (expected " +
         (view.filter == MeshoptFilter::quaternion ? "8" : "4 or 8") + ")");
  if (view.count == 0) fail(at + ".count: 0; expected at least one element");
  if (view.count > kMaxElements)
    fail(at + ".count: " + std::to_string(view.count) + " exceeds the limit of " + std::to_string(kMaxElements));
  const size_t decoded = view.count * stride;  // both bounded above: no overflow
  if (decoded > view_length)
    fail(at + ": count x byteStride is " + std::to_string(decoded) + " bytes; the buffer view has " +
         std::to_string(view_length));
  if (view_length > kMaxFileBytes)
    fail(at + ": a decoded buffer view of " + std::to_string(view_length) + " bytes; expected at most " +
         std::to_string(kMaxFileBytes));
  if (view_length > view.byte_length * kMaxExpansion + kCodecSlack)
    fail(at + ": the buffer view's " + std::to_string(view_length) + " bytes cannot come from " +
         std::to_string(view.byte_length) + " compressed bytes (the codec expands at most " + std::to_string(kMaxExpansion) +
         " times)");
  return view;
}

std::vector<unsigned char> decode_meshopt(const MeshoptView& view, const unsigned char* compressed, size_t view_length,
                                          const std::string& where) {
  std::vector<unsigned char> out(view_length, 0);
  int status = 0;
  switch (view.mode) {
    case MeshoptMode::attributes:
      status = meshopt_decodeVertexBuffer(out.data(), view.count, view.byte_stride, compressed, view.byte_length);
      break;
    case MeshoptMode::triangles:
      status = meshopt_decodeIndexBuffer(out.data(), view.count, view.byte_stride, compressed, view.byte_length);
      break;
    case MeshoptMode::indices:
      status = meshopt_decodeIndexSequence(out.data(), view.count, view.byte_stride, compressed, view.byte_length);
      break;
  }
  if (status != 0)
    fail(where + ".extensions.EXT_meshopt_compression: the compressed data cannot be decoded (meshoptimizer error " +
         std::to_string(status) + ")");
  switch (view.filter) {
    case MeshoptFilter::none:
      break;
    case MeshoptFilter::octahedral:
      meshopt_decodeFilterOct(out.data(), view.count, view.byte_stride);
      break;
    case MeshoptFilter::quaternion:
      meshopt_decodeFilterQuat(out.data(), view.count, view.byte_stride);
      break;
    case MeshoptFilter::exponential:
      meshopt_decodeFilterExp(out.data(), view.count, view.byte_stride);
      break;
  }
  return out;
}

}  // namespace scene::gltf
