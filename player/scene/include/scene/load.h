#pragma once
// One entry point for every scene the player can show: "builtin:NAME" or a .gltf/.glb path.
#include "scene/gltf_loader.h"
#include "scene/scene.h"

#include <iosfwd>
#include <memory>
#include <string>

namespace scene {

// Returns false and says why in `error` (the file, the field and what was expected); loader
// warnings (skipped primitives and the like) go to `log`.
bool load(const std::string& spec, Scene& out, std::string& error, std::ostream& log, const LoadOptions& options = {});

// An environment by spec: "builtin:studio" or empty (null: the built-in studio, which the renderer
// prepares once per process), or an equirectangular HDR/EXR file (scene/environment.h), prepared
// here. False and why.
bool load_environment_spec(const std::string& spec, std::shared_ptr<const Environment>& out, std::string& error);

}  // namespace scene
