// G-buffer and depth prepass vertex stage (HAS_NORMAL_TEXTURE: with tangents; HAS_UV1: a second UV mapping). Positions arrive camera-relative: the model-view matrix
// is composed in double precision on the CPU, so large world coordinates lose nothing here.
// SKINNED: each vertex is first moved by the weighted blend of its four joints' matrices, which a
// texture holds relative to the draw's anchor (see SceneGpu: three RGBA32F texels per joint, the
// rows of its affine matrix, 64 joints to a row of the texture).
// MOTION (an animated scene's temporal AO): the vertex's position at the previous AO frame, through
// the previous model-view (composed with this frame's view, so the difference is the surface's own
// motion in this view's axes) and, SKINNED, the previous pose's joints (the second half of the
// texture's rows); the difference goes to the motion target. A mesh that nothing morphs has its
// own positions as a_previous_position.
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
#ifdef HAS_NORMAL_TEXTURE
layout(location = 3) in vec4 a_tangent;
out vec4 v_view_tangent;
#endif
#ifdef HAS_UV1
layout(location = 4) in vec2 a_uv1;
out vec2 v_uv1;
#endif

#ifdef SKINNED
layout(location = 5) in uvec4 a_joints;
layout(location = 6) in vec4 a_joint_weights;
uniform highp sampler2D u_joint_matrices;
uniform int u_joint_base;

mat4 joint_matrix(int index) {
  ivec2 at = ivec2((index % 64) * 3, index / 64);
  // The texels are the rows; a mat4 is built from columns.
  return transpose(mat4(texelFetch(u_joint_matrices, at, 0), texelFetch(u_joint_matrices, at + ivec2(1, 0), 0),
                        texelFetch(u_joint_matrices, at + ivec2(2, 0), 0), vec4(0.0, 0.0, 0.0, 1.0)));
}

// The vertex's four joints blended, from the joints that start at `base` in the texture.
mat4 skin_matrix(int base) {
  return a_joint_weights.x * joint_matrix(base + int(a_joints.x)) + a_joint_weights.y * joint_matrix(base + int(a_joints.y)) +
         a_joint_weights.z * joint_matrix(base + int(a_joints.z)) + a_joint_weights.w * joint_matrix(base + int(a_joints.w));
}
#endif

#ifdef MOTION
layout(location = 7) in vec3 a_previous_position;
uniform mat4 u_previous_model_view;
out vec3 v_view_motion;
#endif

uniform mat4 u_model_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;

out vec3 v_view_position;
out vec3 v_view_normal;
out vec2 v_uv;
// The depth prepass and the G-buffer pass must produce bit-identical depth for GL_LEQUAL to work.
invariant gl_Position;

void main() {
  vec3 position = a_position;
  vec3 normal = a_normal;
#ifdef HAS_NORMAL_TEXTURE
  vec3 tangent = a_tangent.xyz;
#endif
#ifdef SKINNED
  mat4 skin = skin_matrix(u_joint_base);
  position = (skin * vec4(position, 1.0)).xyz;
  // The blend's linear part for the normal too: exact for rotations and uniform scales, which is
  // what joints carry; the fragment stage normalises.
  normal = mat3(skin) * normal;
#ifdef HAS_NORMAL_TEXTURE
  tangent = mat3(skin) * tangent;
#endif
#endif
  vec4 view = u_model_view * vec4(position, 1.0);
#ifdef MOTION
  vec3 previous = a_previous_position;
#ifdef SKINNED
  previous = (skin_matrix(u_joint_base + (textureSize(u_joint_matrices, 0).y / 2) * 64) * vec4(previous, 1.0)).xyz;
#endif
  v_view_motion = (u_previous_model_view * vec4(previous, 1.0)).xyz - view.xyz;
#endif
  v_view_normal = u_normal_matrix * normal;
  v_uv = a_uv;
#ifdef HAS_NORMAL_TEXTURE
  // A tangent lies in the surface: it turns with the model-view, not with the normal matrix.
  v_view_tangent = vec4(mat3(u_model_view) * tangent, a_tangent.w);
#endif
#ifdef HAS_UV1
  v_uv1 = a_uv1;
#endif
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
