#pragma once
// The bytes of a glTF file before tinygltf sees them: the GLB container checked and rebuilt, JSON
// nesting bounded, and the file-system callbacks that keep every external file inside the scene's
// folder. Errors come back as text (empty: fine), naming the byte or field at fault.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace scene::gltf {

// The largest scene file, and file a scene names (a buffer, an image), that is read: GLB buffers
// index with 32 bits, and a board's memory ends well before this.
inline constexpr std::size_t kMaxFileBytes = std::size_t{2} << 30;

struct Confinement {
  std::filesystem::path root;  // canonical folder of the scene file
};

// tinygltf's FsCallbacks; `user` is a Confinement.
bool confined_exists(const std::string& path, void* user);
std::string confined_expand(const std::string& path, void* user);
bool confined_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user);
bool refuse_write(std::string* err, const std::string& path, const std::vector<unsigned char>& bytes, void* user);

struct Glb {
  std::string json;
  std::string bin;
  bool has_bin = false;
};

// Splits a .glb file's bytes into its chunks; unknown chunks are skipped with a warning.
std::string split_glb(const std::string& bytes, Glb& out, std::vector<std::string>& warnings);
// The same layout rebuilt from checked parts, for tinygltf's reader (which needs BIN right after JSON).
std::string join_glb(const Glb& glb);
// Deeper than kMaxJsonDepth, or empty when the text nests within it.
std::string nesting_problem(const std::string& text);

}  // namespace scene::gltf
