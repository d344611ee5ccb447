// G-buffer: albedo, view-space normal, linear view depth. HAS_BASECOLOR_TEXTURE selects the
// textured variant; untextured materials skip the fetch entirely.
precision highp float;

in vec3 v_view_position;
in vec3 v_view_normal;
in vec2 v_uv;

uniform vec4 u_base_color;
#ifdef HAS_BASECOLOR_TEXTURE
uniform highp sampler2D u_base_color_texture;
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
  vec3 n = v_view_normal;
  float len = length(n);
  // A zero normal (degenerate input) falls back to facing the camera rather than producing NaN.
  n = len > 1e-20 ? n / len : vec3(0.0, 0.0, 1.0);
  if (!gl_FrontFacing) n = -n;
  o_albedo = vec4(albedo.rgb, 1.0);
  o_normal = vec4(n, 1.0);
  o_linear_depth = -v_view_position.z;
#ifdef LIGHTFIELD_MODULES
  o_world_position = vec4(v_world_position, 1.0);
#endif
}
