// Present: upsamples the AO where it was computed at reduced resolution, shades or shows a debug
// output, and writes the result into the platform's framebuffer. Shading (shade.glsl) is glTF's
// metallic-roughness under the environment and the key light or the scene's own lights, plus
// emission; the SSAO term occludes only the environment light. A material's occlusion texture
// joins the SSAO visibility by min(), not a product: a baked occlusion map and SSAO see the same
// creases, and a product would darken them twice (Filament and Frostbite combine them alike).
// ENCODE_SRGB: the framebuffer stores what it is given, so the shader encodes; otherwise the
// framebuffer is sRGB and encodes on write. OUTPUT (OUTPUT_COLOR by default) is a compile-time
// choice: llvmpipe runs every side of a branch on a uniform, and the debug outputs' sRGB decoding
// made the shaded image cost half as much again (21 against 15 ms at 1024x768).
// PRESENT_BOUNDS (fullscreen.vert): drawn over the rectangle of covered_bounds.comp only;
// BACKGROUND_ONLY: the background, drawn over the whole view before it.
#include "common.glsl"
#include "shared_layout.glsl"
#include "upsample.glsl"
#include "gbuffer_normals.glsl"
#include "material.glsl"
#include "shade.glsl"

uniform highp sampler2D u_albedo;
uniform highp sampler2D u_normal;
uniform highp sampler2D u_linear_depth;
uniform highp sampler2D u_ao;  // r = AO (at the AO resolution), g = depth / far
uniform highp usampler2D u_material;

#ifndef OUTPUT
#define OUTPUT OUTPUT_COLOR
#endif

layout(location = 0) out vec4 fragment;

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
#ifdef BACKGROUND_ONLY
  // The view outside the rectangle that holds the surfaces (PRESENT_BOUNDS), as the shading writes it.
  fragment = shaded(composite.background.rgb * composite.fade);
  return;
#endif
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
  if (surface.a < 0.5) {
    fragment = shaded(surface.rgb * fade);
    return;
  }
  highp uvec2 packed_material = texelFetch(u_material, pixel, 0).xy;
  vec4 material = unpackUnorm4x8(packed_material.x);  // roughness, metallic, occlusion
  vec3 view_position = view_position_at(pixel, depth, composite.unproject, ivec2(composite.full_width, composite.full_height));
  // --ao-strength darkens or lightens the shaded image only: the AO view and every read-back show the
  // AO as computed, which is what accuracy is measured on.
  float visibility = min(pow(max(1.0 - ao, 0.0), composite.ao_strength), material.z);
  vec3 color = shade(surface.rgb, material.y, material.x, normal, view_position, visibility);
  color += unpack_rgb9e5(packed_material.y);
  fragment = shaded(color * fade);
#endif
}
