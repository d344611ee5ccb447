// G-buffer: albedo, view-space shading and face normals (gbuffer_normals.glsl), linear view depth.
// HAS_BASECOLOR_TEXTURE selects the textured variant; untextured materials skip the fetch entirely.
// ALPHA_MASK: the alpha-tested variant, only for materials whose alphaMode asks for it.
precision highp float;

#include "gbuffer_normals.glsl"

in vec3 v_view_position;
in vec3 v_view_normal;
in vec2 v_uv;

uniform vec4 u_base_color;
uniform float u_lit;  // 1, or 0 for an unlit material: kept in the albedo's alpha for the present pass
#ifdef HAS_BASECOLOR_TEXTURE
uniform highp sampler2D u_base_color_texture;
#endif
#ifdef ALPHA_MASK
uniform float u_alpha_cutoff;
#endif

layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out float o_linear_depth;
#ifdef LIGHTFIELD_MODULES
in vec3 v_world_position;
layout(location = 3) out vec4 o_world_position;  // the positions texture of Algorithm 2
#endif

void main() {
  vec4 albedo = u_base_color;
#ifdef HAS_BASECOLOR_TEXTURE
  albedo *= texture(u_base_color_texture, v_uv);
#endif
#ifdef ALPHA_MASK
  // glTF's MASK: fully opaque at or above the cutoff, absent below it (the depth prepass cuts alike).
  if (albedo.a < u_alpha_cutoff) discard;
#endif
  vec3 n = v_view_normal;
  float len = length(n);
  // A zero normal (degenerate input) falls back to facing the camera rather than producing NaN.
  n = len > 1e-20 ? n / len : vec3(0.0, 0.0, 1.0);
  if (!gl_FrontFacing) n = -n;
  // The face's plane from the position's screen derivatives: exact, since the quad's helper
  // invocations interpolate this triangle's plane past its edges. Only the plane matters to the
  // horizon, not which way its normal points.
  vec3 face = cross(dFdx(v_view_position), dFdy(v_view_position));
  float face_length = length(face);
  face = face_length > 1e-30 ? face / face_length : n;
  o_albedo = vec4(albedo.rgb, u_lit);
  o_normal = vec4(octahedron_encode(n), octahedron_encode(face));
  o_linear_depth = -v_view_position.z;
#ifdef LIGHTFIELD_MODULES
  o_world_position = vec4(v_world_position, 1.0);
#endif
}
