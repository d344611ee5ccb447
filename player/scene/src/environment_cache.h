#pragma once
// prepare_environment()'s shortcut: the environments it prepared kept on disk
// (keep_prepared_environments() says where), read back by the same build for the same image.
#include "scene/environment.h"

#include <optional>
#include <vector>

namespace scene::detail {

// The kept environment for this image and sizes, when there is one and it reads back whole; its
// name is left for the caller.
std::optional<Environment> kept_environment(int width, int height, const std::vector<float>& rgb, int face_size, int levels);
// Counts `env` as prepared and keeps it, prepared from this image, for the next start. A failure to
// keep it only costs that start the work (environment_cache_counts() says why).
void keep_environment(int width, int height, const std::vector<float>& rgb, const Environment& env);

}  // namespace scene::detail
