#pragma once
// The C++ view of gles_shaders/shared_layout.glsl: the same file, with GLSL's types mapped to GLM
// and to 32-bit scalars. The build checks every block member's offset against std140
// (gles_shaders/layout_check.cmake).
#include <glm/glm.hpp>

#include <cstdint>

namespace shared_layout {
using uint = std::uint32_t;
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
static_assert(sizeof(float) == 4 && sizeof(int) == 4, "std140 scalars are 32 bits");
#include "../../shared_layout.glsl"
}  // namespace shared_layout
