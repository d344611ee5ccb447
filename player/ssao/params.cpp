#include "ssao/params.h"

#include "ssao/tables.h"

#include <algorithm>
#include <cmath>

namespace ssao {

std::string_view name(Blur blur) {
  switch (blur) {
    case Blur::off: return "off";
    case Blur::gaussian: return "gaussian";
    case Blur::bilateral: return "bilateral";
  }
  return "?";
}

std::optional<Blur> parse_blur(std::string_view text) {
  for (Blur blur : {Blur::off, Blur::gaussian, Blur::bilateral})
    if (name(blur) == text) return blur;
  return std::nullopt;
}

shared_layout::SsaoParams make_ssao_params(const AoSettings& settings, float base_radius,
                                           const glm::mat4& projection, int width, int height) {
  shared_layout::SsaoParams params{};
  params.projection = projection;
  params.unproject = glm::vec4(1.0f / projection[0][0], 1.0f / projection[1][1], projection[2][0], projection[2][1]);
  const int samples = std::clamp(settings.samples, 1, SSAO_MAX_SAMPLES);
  const int radii = std::clamp(settings.radii, 1, SSAO_MAX_RADII);
  const std::span<const float> scales = radius_scales();
  params.radii_0_3 = glm::vec4(base_radius * scales[0], base_radius * scales[1], base_radius * scales[2], base_radius * scales[3]);
  params.radius_4_bias = glm::vec4(base_radius * scales[4], settings.bias, 0.0f, 0.0f);
  params.counts = glm::ivec4(samples, radii, width, height);
  const std::span<const glm::vec3> points = kernel(settings.pattern, samples);
  for (int i = 0; i < samples; ++i) params.kernel[i] = glm::vec4(points[static_cast<size_t>(i)], 0.0f);
  const std::span<const float> angles = rotation_angles();
  for (size_t i = 0; i < angles.size(); ++i)
    params.rotation[i] = glm::vec4(std::cos(angles[i]), std::sin(angles[i]), 0.0f, 0.0f);
  return params;
}

shared_layout::BlurParams make_blur_params(const BlurSettings& settings, int direction, int width, int height) {
  shared_layout::BlurParams params{};
  const int radius = std::clamp(settings.radius, 1, BLUR_MAX_RADIUS);
  for (int i = 0; i <= radius; ++i)
    params.weights[i].x = std::exp(-static_cast<float>(i * i) / (2.0f * settings.sigma * settings.sigma));
  params.config = glm::ivec4(radius, direction, width, height);
  params.bilateral = glm::vec4(settings.depth_tolerance, 0.0f, 0.0f, 0.0f);
  return params;
}

}  // namespace ssao
