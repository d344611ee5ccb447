#pragma once
// EXT_meshopt_compression: a buffer view whose bytes are meshoptimizer's vertex or index codec
// output, decoded with Debian's libmeshoptimizer on the loader thread. The request is checked
// before anything is allocated: the decoded size follows from count x byteStride, which must fit
// the buffer view and cannot exceed what the codec can produce from the compressed bytes.
#include <nlohmann/json_fwd.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace scene::gltf {

enum class MeshoptMode { attributes, triangles, indices };
enum class MeshoptFilter { none, octahedral, quaternion, exponential };

struct MeshoptView {
  int buffer = -1;
  size_t byte_offset = 0, byte_length = 0, byte_stride = 0, count = 0;
  MeshoptMode mode = MeshoptMode::attributes;
  MeshoptFilter filter = MeshoptFilter::none;
};

// Reads and checks the extension object of a buffer view of `view_length` bytes (and `view_stride`,
// 0 when absent); throws LoadError naming `where`.
MeshoptView meshopt_view(const nlohmann::json& extension, size_t view_length, size_t view_stride, const std::string& where);

// The buffer view's bytes: `view_length` long, count x byteStride of them decoded, the rest zero.
std::vector<unsigned char> decode_meshopt(const MeshoptView& view, const unsigned char* compressed, size_t view_length,
                                          const std::string& where);

}  // namespace scene::gltf
