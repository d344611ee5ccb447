#pragma once
// glTF 2.0 (.gltf and .glb) to a validated Scene. tinygltf parses; this checks what tinygltf does
// not: the GLB layout, JSON nesting depth, asset.version, the integers and indices glTF's schema
// bounds, accessor and buffer-view bounds, index ranges, non-finite numbers, node cycles, required
// extensions, image sizes before decoding, and that external files stay inside the scene's own folder.
#include "scene/scene.h"

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace scene {

struct LoadReport {
  std::string error;                  // empty on success; names the file, the field and what was expected
  std::vector<std::string> warnings;  // things skipped (non-triangle primitives, undecodable images drawn white)
};

struct LoadOptions {
  // Images wider or taller than this are drawn white (with a warning) instead of being decoded. The
  // loader runs before a GL context may exist, so the default is a size every GLES 3.1 driver we
  // target reaches; a caller that knows GL_MAX_TEXTURE_SIZE passes it here.
  int max_texture_size = 16384;
  // Decoded RGBA bytes one image may take; a file that declares more is drawn white rather than
  // exhausting a board's memory (a 65535 x 65535 PNG header is 100 bytes and asks for 16 GiB).
  size_t image_budget_bytes = size_t{256} << 20;
  // Bytes one scene may decode in all: accessors' elements as the player holds them, decompressed
  // buffer views and images. An accessor without a buffer view or a compressed view is a few bytes
  // of JSON that can ask for gigabytes; such a file is refused naming the field that went over.
  size_t decoded_budget_bytes = size_t{2} << 30;
};

// Deepest JSON nesting accepted (objects and arrays together). Real glTF files nest about ten deep;
// the limit keeps every recursion in tinygltf's JSON handling far from the stack's end.
constexpr int kMaxJsonDepth = 512;

// Returns false and fills report.error on any problem; `out` is then left untouched.
bool load_gltf(const std::filesystem::path& file, Scene& out, LoadReport& report, const LoadOptions& options = {});

}  // namespace scene
