#include "ssao/params.h"

#include "ssao/tables.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace ssao {

std::string_view name(Blur blur) {
  return names::name_of<Blur>(kBlurNames, blur);
}
std::optional<Blur> parse_blur(std::string_view text) {
  return names::parse<Blur>(kBlurNames, text);
}
std::string_view name(Precision precision) {
  return names::name_of<Precision>(kPrecisionNames, precision);
}
std::optional<Precision> parse_precision(std::string_view text) {
  return names::parse<Precision>(kPrecisionNames, text);
}

int horizon_steps(const AoSettings& settings) {
  const int samples = std::clamp(settings.samples, 1, SSAO_MAX_SAMPLES);
  return std::clamp(settings.steps, 1, std::max(1, samples / 2));
}

shared_layout::SsaoParams pack_ssao_params(const AoSettings& settings, float base_radius, int width, int height) {
  shared_layout::SsaoParams params{};
  const int samples = std::clamp(settings.samples, 1, SSAO_MAX_SAMPLES);
  const int radii = std::clamp(settings.radii, 1, SSAO_MAX_RADII);
  const std::span<const float> scales = radius_scales();
  for (int k = 0; k < SSAO_MAX_RADII; ++k) params.radii[k].x = base_radius * scales[static_cast<size_t>(k)];
  params.depth_bias = settings.bias;
  const int shift = settings.half_resolution ? 1 : 0;
  params.samples = samples;
  params.radius_count = radii;
  params.ao_width = (width + shift) >> shift;
  params.ao_height = (height + shift) >> shift;
  params.ao_shift = shift;
  params.full_width = width;
  params.full_height = height;
  params.first_radius = 0;
  params.end_radius = radii;
  params.shade_background = settings.skip_background ? 0 : 1;
  params.horizon_steps = horizon_steps(settings);
  const std::span<const glm::vec3> points = kernel(settings.estimator, settings.pattern, samples);
  for (int i = 0; i < samples; ++i) params.kernel[i] = glm::vec4(points[static_cast<size_t>(i)], 0.0f);
  const std::span<const float> angles = rotation_angles();
  for (size_t i = 0; i < angles.size(); ++i) params.rotation[i] = glm::vec4(std::cos(angles[i]), std::sin(angles[i]), 0.5f, 0.0f);
  return params;
}

void advance_frame(shared_layout::SsaoParams& params, unsigned frame) {
  // R2's first coordinate (Roberts 2018: the generalised golden ratio) for the turn, the golden
  // ratio's own sequence for the taps' place along their steps (R2's second coordinate left gaps of
  // 4/64 in 64 frames, the golden ratio under 2.5/64); fract(n * a) with n counted modulo 2^20 keeps
  // the product exact in double over months of frames.
  constexpr double kPlastic = 1.32471795724474602596, kGolden = 1.61803398874989484820;
  const double n = static_cast<double>(frame % (1u << 20));
  const double turn_share = std::fmod(n / kPlastic, 1.0);
  const double tap_share = std::fmod(n / kGolden, 1.0);
  // A whole turn, not one gap of the tile: every pixel must see every direction over the frames, or
  // its average keeps the tile's pattern (the AO of a still camera stays dithered without a blur).
  const std::span<const float> angles = rotation_angles();
  for (size_t i = 0; i < angles.size(); ++i) {
    const double angle = angles[i] + turn_share * 2.0 * std::numbers::pi;
    // The tile's shares of a step in another order than the turn's Bayer matrix (7 is prime to the
    // tile's 16 entries, so each share once), so that neighbours with close turns do not also have
    // close taps.
    const double entries = static_cast<double>(angles.size());
    const double tap_offset = (static_cast<double>((i * 7 + 3) % angles.size()) + 0.5) / entries;
    const double tap_jitter = std::fmod(tap_share + tap_offset, 1.0);
    params.rotation[i] =
        glm::vec4(static_cast<float>(std::cos(angle)), static_cast<float>(std::sin(angle)), static_cast<float>(tap_jitter), 0.0f);
  }
}

int depth_chain_levels(int width, int height) {
  int levels = 1;
  while (levels < DEPTH_CHAIN_MAX_LEVELS && std::max(width, height) >> levels > 0) ++levels;
  return levels;
}

void update_for_frame(shared_layout::SsaoParams& params, const AoSettings& settings, const FrameView& view) {
  const glm::mat4& projection = view.projection;
  params.projection = projection;
  params.unproject = glm::vec4(1.0f / projection[0][0], 1.0f / projection[1][1], projection[2][0], projection[2][1]);
  const float pixels_per_unit = projection[1][1] * static_cast<float>(params.full_height) * 0.5f;
  params.pixels_per_unit = pixels_per_unit;
  const int radii = params.radius_count;
  const auto radius = [&params](int k) { return params.radii[k].x; };
  // Radii come largest first. One far beyond the scene's size sees the same as the largest one that
  // fits. One under a quarter pixel even where the scene is nearest keeps every sample in the shaded
  // pixel itself, so its result is known without looking: the sphere estimator then hides exactly the
  // samples more than the bias behind the point (whatever the turn); the hemisphere's, all above
  // the tangent plane it compares against, and the horizon's, under a pixel, hide none.
  int first = 0, end = radii;
  params.skipped_radii_ao = 0.0f;
  if (settings.skip_radii) {
    const float too_large = 2.0f * view.scene_radius;
    while (first + 1 < radii && radius(first + 1) >= too_large) ++first;
    while (end > first + 1 && radius(end - 1) * pixels_per_unit / view.nearest_depth < 0.25f) --end;
    if (end < radii && settings.estimator == Estimator::sphere) {
      int behind = 0;
      for (int i = 0; i < params.samples; ++i) behind += params.kernel[i].z < -params.depth_bias ? 1 : 0;
      params.skipped_radii_ao = static_cast<float>(behind) / static_cast<float>(params.samples);
    }
  }
  params.first_radius = first;
  params.end_radius = end;
  params.shade_background = settings.skip_background ? 0 : 1;
  params.horizon_steps = horizon_steps(settings);
  // A radius spanning 2^(k+4) pixels at the scene's centre reads level k: about 16 depth texels
  // across the radius, which is all the point samples can tell apart.
  const int max_level = depth_chain_levels(params.full_width, params.full_height) - 1;
  for (int k = 0; k < SSAO_MAX_RADII; ++k) {
    const float span = radius(k) * pixels_per_unit / view.centre_depth;
    const bool coarse = settings.depth_chain && k < radii && span > 32.0f;
    params.levels[k].x = coarse ? std::min(static_cast<int>(std::floor(std::log2(span / 16.0f))), max_level) : 0;
  }
}

shared_layout::BlurParams pack_blur_params(const BlurSettings& settings, int direction, int width, int height, int shift) {
  shared_layout::BlurParams params{};
  const int radius = std::clamp(settings.radius, 1, BLUR_MAX_RADIUS);
  for (int i = 0; i <= radius; ++i)
    params.weights[i].x = std::exp(-static_cast<float>(i * i) / (2.0f * settings.sigma * settings.sigma));
  params.radius = radius;
  params.direction = direction;
  params.width = width;
  params.height = height;
  params.ao_shift = shift;
  params.depth_tolerance = settings.depth_tolerance;
  return params;
}

}  // namespace ssao
