// A material at the fragment, as glTF describes it: base colour and alpha, the shading normal
// (with the normal map), metallic, roughness, occlusion and emission, from the material's factors
// and the textures its variant has (the HAS_* and *_UV1 defines of gbuffer.frag). The G-buffer pass
// stores it; the forward pass of blended materials shades it at once.
#ifndef SURFACE_GLSL
#define SURFACE_GLSL

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

// Base colour and alpha; ALPHA_MASK discards below the cutoff.
vec4 surface_albedo() {
  vec4 albedo = u_base_color;
#ifdef HAS_BASECOLOR_TEXTURE
  albedo *= texture(u_base_color_texture, v_uv);
#endif
#ifdef ALPHA_MASK
  // glTF's MASK: fully opaque at or above the cutoff, absent below it (the depth prepass cuts alike).
  if (albedo.a < u_alpha_cutoff) discard;
#endif
  return albedo;
}

// The view-space shading normal, towards the viewer on a back face.
vec3 surface_normal() {
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
  return n;
}

void surface_material(out float metallic, out float roughness, out float occlusion, out vec3 emissive) {
  metallic = u_material.x;
  roughness = u_material.y;
  occlusion = 1.0;
#ifdef HAS_METALLIC_ROUGHNESS_TEXTURE
  vec4 metallic_roughness = texture(u_metallic_roughness_texture, METALLIC_ROUGHNESS_UV);
  metallic *= metallic_roughness.b;
  roughness *= metallic_roughness.g;
#endif
#ifdef HAS_OCCLUSION_TEXTURE
  occlusion = 1.0 + u_material.w * (texture(u_occlusion_texture, OCCLUSION_UV).r - 1.0);
#endif
  emissive = u_emissive;
#ifdef HAS_EMISSIVE_TEXTURE
  emissive *= texture(u_emissive_texture, EMISSIVE_UV).rgb;
#endif
}

#endif
