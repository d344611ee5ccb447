#pragma once
// CPU reference of the AO passes: the same algorithm as ssao.comp and blur.comp, step for step, in
// 32-bit floats, rounding to half floats where the GPU stores rgba16f. Tests compare the GPU with it.
#include "gles_shaders/shared_layout.h"

#include <vector>

namespace ssao {

// One pixel of the AO images: x = AO, y = linear depth / far (0 for background).
using AoTexel = glm::vec2;

// linear_depth: width x height, row 0 at the bottom (GL order), 0 for background.
std::vector<AoTexel> reference_ssao(const std::vector<float>& linear_depth, const shared_layout::SsaoParams& params,
                                    float inverse_far);
std::vector<AoTexel> reference_blur(const std::vector<AoTexel>& source, const shared_layout::BlurParams& params,
                                    bool bilateral);

}  // namespace ssao
