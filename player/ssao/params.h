#pragma once
// Settings of the AO passes and the uniform blocks they turn into. The renderer uploads these
// blocks and the CPU reference reads the same ones, so both run on identical inputs.
#include "gles_shaders/shared_layout.h"
#include "ssao/sampling.h"

#include <optional>
#include <string_view>

namespace ssao {

struct AoSettings {
  int samples = 8;                    // per radius, 1..64
  int radii = 5;                      // 1..5, from the radius table, largest first
  Pattern pattern = Pattern::poisson;
  float bias = 0.03f;                 // depth bias as a fraction of each radius
};

enum class Blur { off, gaussian, bilateral };
std::string_view name(Blur blur);
std::optional<Blur> parse_blur(std::string_view text);

struct BlurSettings {
  Blur mode = Blur::gaussian;
  int radius = 4;                     // taps each side, 1..BLUR_MAX_RADIUS
  float sigma = 2.0f;                 // Gaussian sigma in pixels
  float depth_tolerance = 0.05f;      // bilateral: depth difference, relative to depth, that halves trust
};

// `base_radius` is in world (= view) units; `projection` maps view space to clip space.
shared_layout::SsaoParams make_ssao_params(const AoSettings& settings, float base_radius,
                                           const glm::mat4& projection, int width, int height);
// direction 0: horizontal, 1: vertical.
shared_layout::BlurParams make_blur_params(const BlurSettings& settings, int direction, int width, int height);

}  // namespace ssao
