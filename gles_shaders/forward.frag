// Forward pass of blended materials (glTF's alphaMode BLEND): drawn after the present pass, over
// the shaded opaque image, object by object from back to front, blended "over" by the fixed
// function (source alpha, one minus source alpha). The material is read as the G-buffer pass reads
// it (surface.glsl) and shaded at once (shade.glsl); SSAO does not reach a blended surface, which
// is not in the G-buffer, so only its own occlusion texture darkens its environment light.
// Surfaces behind the opaque image are discarded against its linear depth: the platform's
// framebuffer has no depth buffer of the G-buffer's. ENCODE_SRGB as in present.frag; where the
// shader encodes, blending happens between encoded values (an approximation: an sRGB framebuffer
// blends in linear light).
precision highp float;

#include "common.glsl"
#include "surface.glsl"
#include "shade.glsl"

uniform highp sampler2D u_linear_depth;  // the opaque surfaces', 0 where there is none

layout(location = 0) out vec4 fragment;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy) - ivec2(composite.viewport_x, composite.viewport_y);
  float opaque = texelFetch(u_linear_depth, pixel, 0).r;
  // A relative margin for the two rasterisations of one plane (a decal laid on a wall stays in front).
  if (opaque > 0.0 && -v_view_position.z > opaque * (1.0 + 1e-5)) discard;
  vec4 albedo = surface_albedo();
  vec3 color = albedo.rgb;
  if (u_lit > 0.5) {
    float metallic, roughness, occlusion;
    vec3 emissive;
    surface_material(metallic, roughness, occlusion, emissive);
    color = shade(albedo.rgb, metallic, roughness, surface_normal(), v_view_position, occlusion) + emissive;
  }
  color *= composite.fade;
#ifdef ENCODE_SRGB
  fragment = vec4(linear_to_srgb(color), albedo.a);
#else
  fragment = vec4(clamp(color, 0.0, 1.0), albedo.a);
#endif
}
