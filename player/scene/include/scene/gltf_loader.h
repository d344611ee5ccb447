#pragma once
// glTF 2.0 (.gltf and .glb) to a validated Scene. tinygltf parses; this checks what tinygltf does
// not: accessor and buffer-view bounds, index ranges, non-finite numbers, node cycles, required
// extensions, and that external files stay inside the scene's own folder.
#include "scene/scene.h"

#include <filesystem>
#include <string>
#include <vector>

namespace scene {

struct LoadReport {
  std::string error;                  // empty on success; names the file, the field and what was expected
  std::vector<std::string> warnings;  // things skipped (non-triangle primitives, unused texcoord sets)
};

// Returns false and fills report.error on any problem; `out` is then left untouched.
bool load_gltf(const std::filesystem::path& file, Scene& out, LoadReport& report);

}  // namespace scene
