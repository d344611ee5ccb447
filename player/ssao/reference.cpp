#include "ssao/reference.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>

namespace ssao {
namespace {

float to_half(float value) { return glm::unpackHalf1x16(glm::packHalf1x16(value)); }

}  // namespace

std::vector<AoTexel> reference_ssao(const std::vector<float>& linear_depth, const shared_layout::SsaoParams& params,
                                    float inverse_far) {
  const int width = params.counts.z, height = params.counts.w;
  std::vector<AoTexel> out(static_cast<size_t>(width) * static_cast<size_t>(height), AoTexel(0.0f));
  auto depth_at = [&](int x, int y) { return linear_depth[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)]; };
  const float radii[SSAO_MAX_RADII] = {params.radii_0_3.x, params.radii_0_3.y, params.radii_0_3.z,
                                       params.radii_0_3.w, params.radius_4_bias.x};
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float depth = depth_at(x, y);
      if (depth <= 0.0f) continue;
      const glm::vec2 ndc = (glm::vec2(static_cast<float>(x), static_cast<float>(y)) + 0.5f) /
                                glm::vec2(static_cast<float>(width), static_cast<float>(height)) * 2.0f - 1.0f;
      const glm::vec3 position((ndc.x + params.unproject.z) * depth * params.unproject.x,
                               (ndc.y + params.unproject.w) * depth * params.unproject.y, -depth);
      const glm::vec2 turn(params.rotation[(y % SSAO_ROTATION_TILE) * SSAO_ROTATION_TILE + x % SSAO_ROTATION_TILE]);
      float ao = 0.0f;
      for (int k = 0; k < params.counts.y; ++k) {
        const float radius = radii[k];
        const float bias = params.radius_4_bias.y * radius;
        int hidden = 0;
        for (int i = 0; i < params.counts.x; ++i) {
          const glm::vec3 o(params.kernel[i]);
          const glm::vec3 offset(turn.x * o.x - turn.y * o.y, turn.y * o.x + turn.x * o.y, o.z);
          const glm::vec3 sample = position + radius * offset;
          const glm::vec4 clip = params.projection * glm::vec4(sample, 1.0f);
          if (clip.w <= 0.0f) continue;
          const glm::vec2 uv = (glm::vec2(clip) / clip.w * 0.5f + 0.5f) *
                               glm::vec2(static_cast<float>(width), static_cast<float>(height));
          const int tx = static_cast<int>(std::floor(uv.x)), ty = static_cast<int>(std::floor(uv.y));
          if (tx < 0 || ty < 0 || tx >= width || ty >= height) continue;
          const float surface = depth_at(tx, ty);
          const float sample_depth = -sample.z;
          if (surface > 0.0f && surface < sample_depth - bias && std::abs(depth - surface) < radius) ++hidden;
        }
        ao = std::max(ao, static_cast<float>(hidden) / static_cast<float>(params.counts.x));
      }
      out[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)] =
          AoTexel(to_half(ao), to_half(depth * inverse_far));
    }
  }
  return out;
}

std::vector<AoTexel> reference_blur(const std::vector<AoTexel>& source, const shared_layout::BlurParams& params,
                                    bool bilateral) {
  const int width = params.config.z, height = params.config.w;
  const glm::ivec2 step = params.config.y == 0 ? glm::ivec2(1, 0) : glm::ivec2(0, 1);
  std::vector<AoTexel> out(source.size());
  auto at = [&](glm::ivec2 p) { return source[static_cast<size_t>(p.y) * static_cast<size_t>(width) + static_cast<size_t>(p.x)]; };
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::ivec2 pixel(x, y);
      const AoTexel centre = at(pixel);
      AoTexel& result = out[static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x)];
      if (centre.y <= 0.0f) {
        result = centre;
        continue;
      }
      float sum = centre.x * params.weights[0].x;
      float total = params.weights[0].x;
      for (int i = 1; i <= params.config.x; ++i) {
        for (int side = -1; side <= 1; side += 2) {
          const glm::ivec2 tap = glm::clamp(pixel + side * i * step, glm::ivec2(0), glm::ivec2(width - 1, height - 1));
          const AoTexel value = at(tap);
          float weight = params.weights[i].x;
          if (bilateral) {
            const float tolerance = params.bilateral.x * centre.y;
            const float difference = (value.y - centre.y) / tolerance;
            weight *= value.y > 0.0f ? std::exp(-difference * difference) : 0.0f;
          }
          sum += value.x * weight;
          total += weight;
        }
      }
      result = AoTexel(to_half(sum / total), centre.y);
    }
  }
  return out;
}

}  // namespace ssao
