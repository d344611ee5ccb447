#pragma once
// The fixed sample tables, generated at build time by tools/gen_tables from sampling.h and
// compiled in, so the GPU shaders and the CPU reference read the very same numbers.
#include "ssao/sampling.h"

#include <span>

namespace ssao {

inline constexpr int kMaxKernelSamples = 64;

// The kernel of `estimator` and `pattern` with n samples (1..kMaxKernelSamples), see make_kernel.
std::span<const glm::vec3> kernel(Estimator estimator, Pattern pattern, int n);
// Angles of the 4x4 per-pixel rotation tile, row-major.
std::span<const float> rotation_angles();
// Radius fractions of the multi-resolution SSAO, largest first.
std::span<const float> radius_scales();

}  // namespace ssao
