// G-buffer: albedo, view-space shading and face normals (gbuffer_normals.glsl), linear view depth,
// and the material (material.glsl). A variant per feature set a material has, so a scene pays for
// no fetch it does not need: HAS_BASECOLOR_TEXTURE, HAS_METALLIC_ROUGHNESS_TEXTURE,
// HAS_NORMAL_TEXTURE (with the mesh's tangents), HAS_OCCLUSION_TEXTURE, HAS_EMISSIVE_TEXTURE; each
// texture but the base colour's reads the second UV mapping where <NAME>_UV1 is defined.
// ALPHA_MASK: the alpha-tested variant, only for materials whose alphaMode asks for it.
// NO_MATERIAL_TARGET: light field modules on a GPU with four draw buffers (see material.glsl).
precision highp float;

#include "gbuffer_normals.glsl"
#include "material.glsl"

in vec3 v_view_position;
in vec3 v_view_normal;
in vec2 v_uv;
#ifdef HAS_UV1
in vec2 v_uv1;
#endif
#ifdef HAS_NORMAL_TEXTURE
in vec4 v_view_tangent;
#endif

uniform vec4 u_base_color;
uniform float u_lit;  // 1, or 0 for an unlit material: kept in the albedo's alpha for the present pass
// x metallic, y roughness, z normal scale, w occlusion strength (glTF's factors)
uniform vec4 u_material;
uniform vec3 u_emissive;
#ifdef HAS_BASECOLOR_TEXTURE
uniform highp sampler2D u_base_color_texture;
#endif
#ifdef HAS_METALLIC_ROUGHNESS_TEXTURE
uniform highp sampler2D u_metallic_roughness_texture;
#endif
#ifdef HAS_NORMAL_TEXTURE
uniform highp sampler2D u_normal_texture;
uniform float u_frame_handedness;  // -1 where the model-view mirrors
#endif
#ifdef HAS_OCCLUSION_TEXTURE
uniform highp sampler2D u_occlusion_texture;
#endif
#ifdef HAS_EMISSIVE_TEXTURE
uniform highp sampler2D u_emissive_texture;
#endif
#ifdef ALPHA_MASK
uniform float u_alpha_cutoff;
#endif

#ifdef METALLIC_ROUGHNESS_UV1
#define METALLIC_ROUGHNESS_UV v_uv1
#else
#define METALLIC_ROUGHNESS_UV v_uv
#endif
#ifdef NORMAL_UV1
#define NORMAL_UV v_uv1
#else
#define NORMAL_UV v_uv
#endif
#ifdef OCCLUSION_UV1
#define OCCLUSION_UV v_uv1
#else
#define OCCLUSION_UV v_uv
#endif
#ifdef EMISSIVE_UV1
#define EMISSIVE_UV v_uv1
#else
#define EMISSIVE_UV v_uv
#endif

layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out float o_linear_depth;
#ifndef NO_MATERIAL_TARGET
layout(location = 3) out highp uvec2 o_material;
#endif
#ifdef LIGHTFIELD_MODULES
in vec3 v_world_position;
// The positions texture of Algorithm 2, after the material target where there is one.
#ifdef NO_MATERIAL_TARGET
layout(location = 3) out vec4 o_world_position;
#else
layout(location = 4) out vec4 o_world_position;
#endif
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
#ifdef HAS_NORMAL_TEXTURE
  {
    // MikkTSpace's frame: the bitangent from the normal, the tangent and its sign. Both vectors are
    // renormalised and the tangent made orthogonal again, since a scaled node lengthens the tangent
    // and shortens the normal (a model exported in centimetres would lose its map's x); a mirroring
    // node turns the cross product round, u_frame_handedness turns it back. A back face turns the
    // whole frame.
    vec3 geometric = len > 1e-20 ? v_view_normal / len : vec3(0.0, 0.0, 1.0);
    vec3 t = v_view_tangent.xyz - geometric * dot(geometric, v_view_tangent.xyz);
    float t_length = length(t);
    t = t_length > 1e-20 ? t / t_length : normalize(cross(geometric, abs(geometric.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0)));
    vec3 b = (v_view_tangent.w < 0.0 ? -u_frame_handedness : u_frame_handedness) * cross(geometric, t);
    if (!gl_FrontFacing) {
      t = -t;
      b = -b;
    }
    vec3 m = texture(u_normal_texture, NORMAL_UV).xyz * 2.0 - 1.0;
    m.xy *= u_material.z;
    vec3 mapped = m.x * t + m.y * b + m.z * n;
    float mapped_length = length(mapped);
    if (mapped_length > 1e-20) n = mapped / mapped_length;
  }
#endif
  // The face's plane from the position's screen derivatives: exact, since the quad's helper
  // invocations interpolate this triangle's plane past its edges. Only the plane matters to the
  // horizon, not which way its normal points.
  vec3 face = cross(dFdx(v_view_position), dFdy(v_view_position));
  float face_length = length(face);
  face = face_length > 1e-30 ? face / face_length : n;
  o_albedo = vec4(albedo.rgb, u_lit);
#ifndef NO_MATERIAL_TARGET
  float metallic = u_material.x, roughness = u_material.y, occlusion = 1.0;
#ifdef HAS_METALLIC_ROUGHNESS_TEXTURE
  vec4 metallic_roughness = texture(u_metallic_roughness_texture, METALLIC_ROUGHNESS_UV);
  metallic *= metallic_roughness.b;
  roughness *= metallic_roughness.g;
#endif
#ifdef HAS_OCCLUSION_TEXTURE
  occlusion = 1.0 + u_material.w * (texture(u_occlusion_texture, OCCLUSION_UV).r - 1.0);
#endif
  vec3 emissive = u_emissive;
#ifdef HAS_EMISSIVE_TEXTURE
  emissive *= texture(u_emissive_texture, EMISSIVE_UV).rgb;
#endif
  o_material = uvec2(packUnorm4x8(vec4(roughness, metallic, occlusion, 0.0)), pack_rgb9e5(emissive));
#endif
  o_normal = vec4(octahedron_encode(n), octahedron_encode(face));
  o_linear_depth = -v_view_position.z;
#ifdef LIGHTFIELD_MODULES
  o_world_position = vec4(v_world_position, 1.0);
#endif
}
