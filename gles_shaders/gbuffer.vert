// G-buffer and depth prepass vertex stage. Positions arrive camera-relative: the model-view matrix
// is composed in double precision on the CPU, so large world coordinates lose nothing here.
// LIGHTFIELD_MODULES: u_model_view takes the model to physical space, the module's world-to-image
// transform (lightfield.glsl) places the vertex, and the world position goes to the positions texture.
precision highp float;
#ifdef LIGHTFIELD_MODULES
#include "lightfield.glsl"
out vec3 v_world_position;
#endif

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec2 a_uv;

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;

out vec3 v_view_position;
out vec3 v_view_normal;
out vec2 v_uv;
// The depth prepass and the G-buffer pass must produce bit-identical depth for GL_LEQUAL to work.
invariant gl_Position;

void main() {
  vec4 view = u_model_view * vec4(a_position, 1.0);
  v_view_normal = u_normal_matrix * a_normal;
  v_uv = a_uv;
#ifdef LIGHTFIELD_MODULES
  // Physical space looks like view space from the observer line: +z towards the viewer, so the
  // normal needs no change and the linear depth is the distance from the observer line.
  v_world_position = (lightfield_module.physical_to_world * view).xyz;
  v_view_position = vec3(view.xy, -module_depth(view.xyz));
  gl_Position = module_clip(view.xyz);
#else
  v_view_position = view.xyz;
  gl_Position = u_projection * view;
#endif
}
