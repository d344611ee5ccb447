#pragma once
#include <string_view>

namespace gles_shaders {
// The shader file `name` (e.g. "ssao.comp") with its #includes resolved, without a #version line;
// empty if there is no such shader.
std::string_view source(std::string_view name);
}  // namespace gles_shaders
