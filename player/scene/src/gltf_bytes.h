#pragma once
// The bytes of a glTF file: the GLB container checked and split, JSON nesting bounded, data: URIs
// decoded, and external files read only from inside the scene's folder. Errors come back as text (empty: fine), naming the byte
// or field at fault.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace scene::gltf {

// The largest scene file, and file a scene names (a buffer, an image), that is read: GLB buffers
// index with 32 bits, and a board's memory ends well before this.
inline constexpr std::size_t kMaxFileBytes = std::size_t{2} << 30;

// Reads `uri` (percent-encoded, relative to `folder`) as a regular file, refused when it resolves
// outside `folder` (through "..", or a symbolic link). Returns false with the reason in `problem`.
bool read_confined(const std::filesystem::path& folder, const std::string& uri, std::vector<unsigned char>& out,
                   std::string& problem);

// A data: URI's bytes (RFC 2397: base64, or percent-encoded text). False with the reason in `problem`.
bool decode_data_uri(const std::string& uri, std::vector<unsigned char>& out, std::string& problem);

// External files may only be named relative to the scene's folder and may not climb out of it:
// the reason a uri is refused, or empty.
std::string uri_problem(const std::string& uri);

struct Glb {
  std::string json;
  std::string bin;
  bool has_bin = false;
};

// Splits a .glb file's bytes into its chunks; unknown chunks are skipped with a warning.
std::string split_glb(const std::string& bytes, Glb& out, std::vector<std::string>& warnings);
// Deeper than kMaxJsonDepth, or empty when the text nests within it.
std::string nesting_problem(const std::string& text);

}  // namespace scene::gltf
