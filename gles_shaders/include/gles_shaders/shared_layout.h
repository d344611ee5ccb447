#pragma once
// The C++ view of gles_shaders/shared_layout.glsl: the same file, with GLSL's types mapped to GLM.
#include <glm/glm.hpp>

namespace shared_layout {
using vec4 = glm::vec4;
using ivec4 = glm::ivec4;
using mat4 = glm::mat4;
#include "../../shared_layout.glsl"

// std140 lays these out exactly as C++ does only if every member is a 16-byte multiple.
static_assert(sizeof(SsaoParams) == 64 + 16 * 7 + 16 * SSAO_MAX_SAMPLES + 16 * SSAO_ROTATION_TILE * SSAO_ROTATION_TILE);
static_assert(sizeof(UpsampleParams) == 48);
static_assert(sizeof(BlurParams) == 16 * (BLUR_MAX_RADIUS + 1) + 48);
static_assert(sizeof(CompositeParams) == 128);
static_assert(sizeof(TemporalParams) == 64 * 3 + 16 * 4);
}  // namespace shared_layout
