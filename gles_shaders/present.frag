// Present: upsamples the AO where it was computed at reduced resolution, shades (ambient + one
// directional light in view space, times 1 - AO) or shows a debug output, and writes the result
// into the platform's framebuffer. ENCODE_SRGB: the framebuffer stores what it is given, so the
// shader encodes; otherwise the framebuffer is sRGB and encodes on write. OUTPUT (OUTPUT_COLOR by
// default) is a compile-time choice: llvmpipe runs every side of a branch on a uniform, and the
// debug outputs' sRGB decoding made the shaded image cost half as much again (21 against 15 ms at
// 1024x768).
#include "common.glsl"
#include "shared_layout.glsl"
#include "upsample.glsl"
#include "gbuffer_normals.glsl"

layout(std140, binding = BINDING_COMPOSITE_PARAMS) uniform CompositeBlock { CompositeParams composite; };
uniform highp sampler2D u_albedo;
uniform highp sampler2D u_normal;
uniform highp sampler2D u_linear_depth;
uniform highp sampler2D u_ao;  // r = AO (at the AO resolution), g = depth / far

#ifndef OUTPUT
#define OUTPUT OUTPUT_COLOR
#endif

layout(location = 0) out vec4 fragment;

vec3 linear_to_srgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}
vec3 srgb_to_linear(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}

// Shaded colour is linear; data outputs (normal, depth) are to arrive in the framebuffer as they are.
vec4 shaded(vec3 linear) {
#ifdef ENCODE_SRGB
  return vec4(linear_to_srgb(linear), 1.0);
#else
  return vec4(clamp(linear, 0.0, 1.0), 1.0);
#endif
}
vec4 data(vec3 value) {
#ifdef ENCODE_SRGB
  return vec4(value, 1.0);
#else
  return vec4(srgb_to_linear(clamp(value, 0.0, 1.0)), 1.0);
#endif
}

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy) - ivec2(composite.viewport_x, composite.viewport_y);
  float fade = composite.fade;
  float depth = texelFetch(u_linear_depth, pixel, 0).r;
  if (depth <= 0.0) {
    fragment = shaded(composite.background.rgb * fade);
    return;
  }
  // Fetched once for the upsampling's plane weights and the shading: the two fetches sat in
  // different branches, where the compiler could not merge them.
  vec3 normal = shading_normal(texelFetch(u_normal, pixel, 0));
  float ao = 0.0;
  if (composite.apply_ao != 0) {
    if (composite.ao_shift == 0) ao = texelFetch(u_ao, pixel, 0).r;
    else
      ao = upsampled_ao(u_ao, u_linear_depth, composite.inverse_far, ivec2(composite.ao_width, composite.ao_height),
                        pixel, depth * composite.inverse_far, vec4(normal, composite.plane_tolerance),
                        composite.unproject, ivec2(composite.full_width, composite.full_height));
  }
#if OUTPUT == OUTPUT_AO
  fragment = shaded(vec3(1.0 - ao) * fade);
#elif OUTPUT == OUTPUT_NORMAL
  fragment = data((normal * 0.5 + 0.5) * fade);
#elif OUTPUT == OUTPUT_DEPTH
  float t = (depth - composite.near_plane) / (composite.far_plane - composite.near_plane);
  fragment = data(vec3(1.0 - clamp(t, 0.0, 1.0)) * fade);
#else
  vec4 surface = texelFetch(u_albedo, pixel, 0);  // a = 0: an unlit material (KHR_materials_unlit)
  float ambient = composite.ambient;
  float diffuse = max(dot(normal, composite.light_direction.xyz), 0.0);
  // --ao-strength darkens or lightens the shaded image only: the AO view and every read-back show the
  // AO as computed, which is what accuracy is measured on.
  float visibility = pow(max(1.0 - ao, 0.0), composite.ao_strength);
  // A select, not a mix: lit pixels keep exactly the value they had before unlit materials existed.
  float light = surface.a > 0.5 ? (ambient + (1.0 - ambient) * diffuse) * visibility : 1.0;
  fragment = shaded(surface.rgb * light * fade);
#endif
}
