#include "ssao/reference.h"

#include "ssao/params.h"

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>

namespace ssao {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kUpsampleDepthTolerance = 0.05f;  // upsample.glsl's UPSAMPLE_DEPTH_TOLERANCE
constexpr float kHorizonFadeEnd = 2.0f;           // ssao.comp's HORIZON_FADE_END
constexpr float kHorizonNearTapPixels = 1.6f;     // ssao.comp's HORIZON_NEAR_TAP_PIXELS
constexpr float kHorizonElevationCap = 20.0f;     // ssao.comp's HORIZON_ELEVATION_CAP

// ssao.comp's tap_distance_pixels.
float tap_distance_pixels(int step, int steps, float radius_pixels, float jitter) {
  if (steps == 1) return radius_pixels;
  const float spacing = radius_pixels / static_cast<float>(steps - 1);
  if (step == 0)
    return std::min(glm::mix(kHorizonNearTapPixels, std::max(0.5f * spacing, kHorizonNearTapPixels), jitter), radius_pixels);
  return std::max((static_cast<float>(step) + jitter - 0.5f) * spacing, static_cast<float>(step));
}

float to_half(float value) {
  return glm::unpackHalf1x16(glm::packHalf1x16(value));
}

// common.glsl's view_position_at: the view-space point at `depth` behind the centre of `pixel`.
glm::vec3 view_position_at(glm::ivec2 pixel, float depth, glm::vec4 unproject, glm::ivec2 size) {
  const glm::vec2 ndc = (glm::vec2(pixel) + 0.5f) / glm::vec2(size) * 2.0f - 1.0f;
  return {(ndc.x + unproject.z) * depth * unproject.x, (ndc.y + unproject.w) * depth * unproject.y, -depth};
}

size_t index(glm::ivec2 p, int width) {
  return static_cast<size_t>(p.y) * static_cast<size_t>(width) + static_cast<size_t>(p.x);
}

bool outside(glm::ivec2 p, glm::ivec2 size) {
  return p.x < 0 || p.y < 0 || p.x >= size.x || p.y >= size.y;
}

// ssao.comp on the CPU: the block and depth chain it reads, and its functions over them.
struct SsaoMirror {
  const DepthChain& depth;
  const shared_layout::SsaoParams& p;
  glm::ivec2 full;

  float radius_at(int k) const { return p.radii[k].x; }
  int level_at(int k) const { return p.levels[k].x; }
  float depth_at(glm::ivec2 texel, int level) const {
    const glm::ivec2 size = depth.sizes[static_cast<size_t>(level)];
    return depth.at(glm::min(glm::ivec2(texel.x >> level, texel.y >> level), size - 1), level);
  }
  glm::vec3 view_position(glm::ivec2 texel, float d) const { return view_position_at(texel, d, p.unproject, full); }

  float plane_depth(glm::vec2 ndc, glm::vec3 normal, float plane) const {
    const float facing =
        glm::dot(normal, glm::vec3((ndc.x + p.unproject.z) * p.unproject.x, (ndc.y + p.unproject.w) * p.unproject.y, -1.0f));
    return facing < -1e-4f ? plane / facing : 0.0f;
  }
  // The hemisphere estimator's correction of the stored depth to the sample's exact position: see
  // subtexel_shift in ssao.comp.
  float subtexel_shift(glm::vec2 ndc, glm::ivec2 texel, int level, glm::vec3 normal, float plane, float radius) const {
    const glm::ivec2 coarse =
        glm::min(glm::ivec2(texel.x >> level, texel.y >> level), depth.sizes[static_cast<size_t>(level)] - 1);
    const glm::vec2 centre = (glm::vec2(coarse) + 0.5f) * static_cast<float>(1 << level) / glm::vec2(full) * 2.0f - 1.0f;
    const float exact = plane_depth(ndc, normal, plane), at_centre = plane_depth(centre, normal, plane);
    return exact > 0.0f && at_centre > 0.0f ? std::clamp(exact - at_centre, -radius, radius) : 0.0f;
  }

  // `mediump` rounds what ssao.comp declares SAMPLE_PRECISION to half floats, emulating AO_MEDIUMP.
  float hidden_share(glm::vec3 position, float d, const glm::mat3& basis, float radius, int level, bool mediump,
                     bool shift_to_sample) const {
    const auto sample_precision = [mediump](float v) { return mediump ? to_half(v) : v; };
    const float bias = sample_precision(p.depth_bias * radius);
    const glm::vec4 clip_centre = p.projection * glm::vec4(position, 1.0f);
    const float plane = glm::dot(basis[2], position);
    int hidden = 0;
    for (int i = 0; i < p.samples; ++i) {
      glm::vec3 offset = radius * (basis * glm::vec3(p.kernel[i]));
      for (int c = 0; c < 3; ++c) offset[c] = sample_precision(offset[c]);
      const glm::vec4 clip = clip_centre + p.projection * glm::vec4(offset, 0.0f);
      if (clip.w <= 0.0f) continue;
      const glm::vec2 ndc = glm::vec2(clip) / clip.w;
      const glm::vec2 uv = (ndc * 0.5f + 0.5f) * glm::vec2(full);
      const glm::ivec2 texel(static_cast<int>(std::floor(uv.x)), static_cast<int>(std::floor(uv.y)));
      if (outside(texel, full)) continue;
      float surface = depth_at(texel, level);
      if (shift_to_sample && surface > 0.0f) surface += subtexel_shift(ndc, texel, level, basis[2], plane, radius);
      const float surface_offset = sample_precision(surface - d);
      const float sample_offset = sample_precision(-offset.z);
      if (surface > 0.0f && surface_offset < sample_offset - bias && std::abs(surface_offset) < radius) ++hidden;
    }
    return static_cast<float>(hidden) / static_cast<float>(p.samples);
  }

  // No `mediump` here: ssao.comp's horizon keeps every per-tap value highp in its mediump variant.
  float horizon_occlusion(glm::ivec2 pixel, glm::vec3 position, glm::vec3 normal, glm::vec3 face, float d, float turn_angle,
                          float tap_jitter, float radius, int level) const {
    const float radius_pixels = radius * p.pixels_per_unit / d;
    if (radius_pixels < 1.0f) return 0.0f;
    const int steps = p.horizon_steps;
    const int slices = std::max(1, p.samples / (2 * steps));
    const glm::vec3 view = glm::normalize(-position);
    // ssao.comp's per-pixel form of view_position for the taps.
    const glm::vec2 unproject_scale(p.unproject.x, p.unproject.y), unproject_shift(p.unproject.z, p.unproject.w);
    const glm::vec2 tap_scale = 2.0f * unproject_scale / glm::vec2(full);
    const glm::vec2 tap_offset = (1.0f / glm::vec2(full) - 1.0f + unproject_shift) * unproject_scale;
    const float inverse_radius = 1.0f / radius;
    float visibility = 0.0f, open = 0.0f;
    for (int slice = 0; slice < slices; ++slice) {
      const float phi = (kPi * static_cast<float>(slice) + 0.5f * turn_angle) / static_cast<float>(slices);
      const glm::vec2 direction(std::cos(phi), std::sin(phi));
      const glm::vec3 direction_view(direction, 0.0f);
      const glm::vec3 ortho = direction_view - glm::dot(direction_view, view) * view;
      const glm::vec3 axis = glm::normalize(glm::cross(ortho, view));
      const glm::vec3 projected_normal = normal - axis * glm::dot(normal, axis);
      const float projected_length = glm::length(projected_normal);
      if (projected_length < 1e-6f) continue;
      const float cos_normal = std::clamp(glm::dot(projected_normal, view) / projected_length, -1.0f, 1.0f);
      const float side_sign = glm::dot(ortho, projected_normal);
      const float gamma = (side_sign > 0.0f ? 1.0f : side_sign < 0.0f ? -1.0f : 0.0f) * std::acos(cos_normal);
      const glm::vec3 tangent_plus = glm::cross(projected_normal, axis) / projected_length;
      // The face's own plane bounds the horizons first (ssao.comp says why).
      glm::vec3 face_trace = glm::cross(axis, face);
      if (glm::dot(face_trace, tangent_plus) < 0.0f) face_trace = -face_trace;
      const float face_along = glm::dot(face_trace, tangent_plus) * projected_length;
      const float face_rise = glm::dot(face_trace, normal);
      float elevation_plus = face_rise > 0.0f ? face_rise / (face_along + face_rise) : 0.0f;
      float elevation_minus = face_rise < 0.0f ? -face_rise / (face_along - face_rise) : 0.0f;
      for (int step = 0; step < steps; ++step) {
        const float distance_pixels = tap_distance_pixels(step, steps, radius_pixels, tap_jitter);
        for (int side = 0; side < 2; ++side) {
          const glm::vec2 offset = (side == 0 ? 1.0f : -1.0f) * distance_pixels * direction;
          const glm::ivec2 texel =
              pixel + glm::ivec2(static_cast<int>(std::floor(offset.x + 0.5f)), static_cast<int>(std::floor(offset.y + 0.5f)));
          if (outside(texel, full)) continue;
          const float sample_depth = depth_at(texel, level);
          if (sample_depth <= 0.0f) continue;
          // ssao.comp keeps every per-tap value of the horizon highp in its mediump variant too.
          const glm::vec3 delta =
              (glm::vec3((glm::vec2(texel) * tap_scale + tap_offset) * sample_depth, -sample_depth) - position) * inverse_radius;
          const float distance = glm::length(delta);
          if (distance >= kHorizonFadeEnd || distance <= 0.0f) continue;
          const float rise = glm::dot(delta, normal);
          if (rise <= 0.0f) continue;
          const float along = glm::dot(delta, tangent_plus) * (side == 0 ? projected_length : -projected_length);
          const float share = rise / (std::abs(along) + rise);  // ssao.comp's pseudo-angle
          float elevation = std::min(along >= 0.0f ? share : 2.0f - share, kHorizonElevationCap * share);
          if (distance > 1.0f) elevation *= (kHorizonFadeEnd - distance) / (kHorizonFadeEnd - 1.0f);
          if (side == 0)
            elevation_plus = std::max(elevation_plus, elevation);
          else
            elevation_minus = std::max(elevation_minus, elevation);
        }
      }
      const auto radians = [](float pseudo) { return std::atan2(std::min(pseudo, 2.0f - pseudo), 1.0f - pseudo); };
      elevation_plus = radians(elevation_plus);
      elevation_minus = radians(elevation_minus);
      const float h1 = gamma + 0.5f * kPi - std::min(elevation_plus, std::max(gamma + 0.5f * kPi, 0.0f));
      const float h0 = gamma - 0.5f * kPi + std::min(elevation_minus, std::max(0.5f * kPi - gamma, 0.0f));
      const auto arc_integral = [&](float h) {
        return (cos_normal + 2.0f * h * std::sin(gamma) - std::cos(2.0f * h - gamma)) * 0.25f;
      };
      visibility += projected_length * (arc_integral(h0) + arc_integral(h1));
      open += projected_length * (cos_normal + gamma * std::sin(gamma));  // the whole open arc, as ssao.comp
    }
    // The occluded share of the open arcs: see horizon_occlusion in ssao.comp.
    return open > 0.0f ? std::clamp(1.0f - visibility / open, 0.0f, 1.0f) : 0.0f;
  }
};

}  // namespace

float DepthChain::at(glm::ivec2 texel, int level) const {
  return levels[static_cast<size_t>(level)][index(texel, sizes[static_cast<size_t>(level)].x)];
}

DepthChain build_depth_chain(const std::vector<float>& linear_depth, int width, int height) {
  DepthChain chain;
  chain.levels.push_back(linear_depth);
  chain.sizes.emplace_back(width, height);
  const int count = depth_chain_levels(width, height);
  for (int level = 1; level < count; ++level) {
    const glm::ivec2 source_size = chain.sizes.back();
    const glm::ivec2 size(std::max(source_size.x >> 1, 1), std::max(source_size.y >> 1, 1));
    std::vector<float> values(static_cast<size_t>(size.x) * static_cast<size_t>(size.y));
    const std::vector<float>& source = chain.levels.back();
    for (int y = 0; y < size.y; ++y)
      for (int x = 0; x < size.x; ++x) {
        float sum = 0.0f;
        int valid = 0;
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx) {
            const glm::ivec2 s(x * 2 + dx, y * 2 + dy);
            if (s.x >= source_size.x || s.y >= source_size.y) continue;
            const float d = source[index(s, source_size.x)];
            if (d > 0.0f) {
              sum += d;
              ++valid;
            }
          }
        values[index({x, y}, size.x)] = valid > 0 ? sum / static_cast<float>(valid) : 0.0f;
      }
    chain.levels.push_back(std::move(values));
    chain.sizes.push_back(size);
  }
  return chain;
}

std::vector<AoTexel> reference_ssao(const DepthChain& depth, const std::vector<glm::vec3>& view_normals,
                                    const std::vector<glm::vec3>& view_face_normals, const shared_layout::SsaoParams& params,
                                    float inverse_far, Estimator estimator, bool mediump) {
  const SsaoMirror shader{depth, params, glm::ivec2(params.full_width, params.full_height)};
  const int width = params.ao_width, height = params.ao_height;
  std::vector<AoTexel> out(static_cast<size_t>(width) * static_cast<size_t>(height), AoTexel(0.0f));
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::ivec2 pixel(x << params.ao_shift, y << params.ao_shift);
      const float d = depth.at(pixel, 0);
      if (d <= 0.0f) continue;
      const glm::vec3 position = shader.view_position(pixel, d);
      const glm::vec4 tile_entry =
          params.rotation[(pixel.y % SSAO_ROTATION_TILE) * SSAO_ROTATION_TILE + pixel.x % SSAO_ROTATION_TILE];
      const glm::vec2 turn(tile_entry);
      const glm::vec3 normal = view_normals.empty() ? glm::vec3(0, 0, 1) : view_normals[index(pixel, shader.full.x)];
      const glm::vec3 face = view_face_normals.empty() ? normal : view_face_normals[index(pixel, shader.full.x)];
      glm::mat3 basis(turn.x, turn.y, 0.0f, -turn.y, turn.x, 0.0f, 0.0f, 0.0f, 1.0f);
      if (estimator == Estimator::hemisphere) {
        const glm::vec3 reference(turn, 0.0f);
        glm::vec3 tangent = reference - normal * glm::dot(reference, normal);
        if (glm::dot(tangent, tangent) < 1e-6f) {
          const glm::vec3 other(-turn.y, turn.x, 0.0f);
          tangent = other - normal * glm::dot(other, normal);
        }
        tangent = glm::normalize(tangent);
        basis = glm::mat3(tangent, glm::cross(normal, tangent), normal);
      }
      float ao = params.skipped_radii_ao;
      for (int k = params.first_radius; k < params.end_radius; ++k) {
        const float radius = shader.radius_at(k);
        const int level = shader.level_at(k);
        ao = std::max(
            ao, estimator == Estimator::horizon
                    ? shader.horizon_occlusion(pixel, position, normal, face, d, std::atan2(turn.y, turn.x), tile_entry.z, radius,
                                               level)
                    : shader.hidden_share(position, d, basis, radius, level, mediump, estimator == Estimator::hemisphere));
      }
      out[index({x, y}, width)] = AoTexel(to_half(ao), to_half(d * inverse_far));
    }
  }
  return out;
}

std::vector<AoTexel> reference_blur(const std::vector<AoTexel>& source, const shared_layout::BlurParams& params, Blur mode,
                                    const std::vector<glm::vec3>& view_normals, int full_width) {
  const bool bilateral = mode == Blur::bilateral || mode == Blur::denoise;
  const bool denoise = mode == Blur::denoise;
  const auto normal_at = [&](glm::ivec2 texel) { return view_normals[index(texel * (1 << params.ao_shift), full_width)]; };
  const int width = params.width, height = params.height;
  const glm::ivec2 step = params.direction == 0 ? glm::ivec2(1, 0) : glm::ivec2(0, 1);
  std::vector<AoTexel> out(source.size());
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const glm::ivec2 pixel(x, y);
      const AoTexel centre = source[index(pixel, width)];
      AoTexel& result = out[index(pixel, width)];
      if (centre.y <= 0.0f) {
        result = centre;
        continue;
      }
      float sum = centre.x * params.weights[0].x;
      float total = params.weights[0].x;
      for (int i = 1; i <= params.radius; ++i) {
        for (int side = -1; side <= 1; side += 2) {
          const glm::ivec2 tap = glm::clamp(pixel + side * i * step, glm::ivec2(0), glm::ivec2(width - 1, height - 1));
          const AoTexel value = source[index(tap, width)];
          float weight = params.weights[i].x;
          if (bilateral) {
            const float tolerance = params.depth_tolerance * centre.y;
            const float difference = (value.y - centre.y) / tolerance;
            weight *= value.y > 0.0f ? std::exp(-difference * difference) : 0.0f;
          }
          if (denoise) {
            float agreement = std::max(glm::dot(normal_at(pixel), normal_at(tap)), 0.0f);
            agreement *= agreement;
            agreement *= agreement;
            weight *= agreement * agreement;  // blur.comp: cos^8 by three squarings
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

std::vector<AoTexel> reference_upsample(const std::vector<AoTexel>& low, const std::vector<float>& linear_depth,
                                        const shared_layout::UpsampleParams& params, const std::vector<glm::vec3>& view_normals) {
  const glm::ivec2 full(params.full_width, params.full_height), small(params.ao_width, params.ao_height);
  const float plane_tolerance = view_normals.empty() ? 0.0f : params.plane_tolerance;
  std::vector<AoTexel> out(static_cast<size_t>(full.x) * static_cast<size_t>(full.y), AoTexel(0.0f));
  for (int y = 0; y < full.y; ++y)
    for (int x = 0; x < full.x; ++x) {
      const float depth = linear_depth[index({x, y}, full.x)] * params.inverse_far;
      if (depth <= 0.0f) continue;
      // upsample.glsl: bilinear among the texels on the pixel's own surface, weighed down the further
      // their points lie off its tangent plane; else the closest in depth.
      const glm::vec2 f(static_cast<float>(x & 1) * 0.5f, static_cast<float>(y & 1) * 0.5f);
      const glm::vec3 normal = plane_tolerance > 0.0f ? view_normals[index({x, y}, full.x)] : glm::vec3(0.0f);
      const float facing = glm::dot(view_position_at({x, y}, 1.0f, params.unproject, full), normal);
      const glm::vec2 step_along_normal =
          2.0f * glm::vec2(params.unproject.x, params.unproject.y) / glm::vec2(full) * glm::vec2(normal.x, normal.y);
      const float sharpness = plane_tolerance > 0.0f ? 1.0f / (plane_tolerance * depth) : 0.0f;
      float best_difference = 1e30f, best_ao = 0.0f, weight_sum = 0.0f, ao_sum = 0.0f;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          float weight = (dx == 0 ? 1.0f - f.x : f.x) * (dy == 0 ? 1.0f - f.y : f.y);
          if (weight <= 0.0f) continue;
          const glm::ivec2 texel = glm::min(glm::ivec2(x >> 1, y >> 1) + glm::ivec2(dx, dy), small - 1);
          const float value = low[index(texel, small.x)].x;
          const float texel_depth = linear_depth[index(texel * 2, full.x)] * params.inverse_far;
          if (texel_depth <= 0.0f) continue;
          const float difference = std::abs(texel_depth - depth);
          if (difference < best_difference) {
            best_difference = difference;
            best_ao = value;
          }
          if (difference <= kUpsampleDepthTolerance * depth) {
            const glm::vec2 offset(texel * 2 - glm::ivec2(x, y));
            const float height = (texel_depth - depth) * facing + texel_depth * glm::dot(offset, step_along_normal);
            weight *= std::exp(-std::abs(height) * sharpness);
            weight_sum += weight;
            ao_sum += weight * value;
          }
        }
      const float ao = weight_sum > 0.0f ? to_half(ao_sum / weight_sum) : best_ao;
      out[index({x, y}, full.x)] = AoTexel(ao, to_half(depth));
    }
  return out;
}

}  // namespace ssao
