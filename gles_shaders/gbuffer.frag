// G-buffer: albedo, view-space shading and face normals (gbuffer_normals.glsl), linear view depth,
// and the material (material.glsl). A variant per feature set a material has, so a scene pays for
// no fetch it does not need: HAS_BASECOLOR_TEXTURE, HAS_METALLIC_ROUGHNESS_TEXTURE,
// HAS_NORMAL_TEXTURE (with the mesh's tangents), HAS_OCCLUSION_TEXTURE, HAS_EMISSIVE_TEXTURE; each
// texture but the base colour's reads the second UV mapping where <NAME>_UV1 is defined.
// ALPHA_MASK: the alpha-tested variant, only for materials whose alphaMode asks for it.
// MOTION: the surface point's motion since the previous AO frame, in this view's space (gbuffer.vert),
// for temporal.comp to find the point's history where it was, not where the camera alone puts it.
// NO_MATERIAL_TARGET: light field modules on a GPU with four draw buffers (see material.glsl).
precision highp float;

#include "gbuffer_normals.glsl"
#include "material.glsl"
#include "surface.glsl"

layout(location = 0) out vec4 o_albedo;
layout(location = 1) out vec4 o_normal;
layout(location = 2) out float o_linear_depth;
#ifndef NO_MATERIAL_TARGET
layout(location = 3) out highp uvec2 o_material;
#endif
#ifdef MOTION
in vec3 v_view_motion;
layout(location = 4) out vec4 o_motion;  // never with LIGHTFIELD_MODULES: modules keep no history
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
  vec4 albedo = surface_albedo();
  vec3 n = surface_normal();
  // The face's plane from the position's screen derivatives: exact, since the quad's helper
  // invocations interpolate this triangle's plane past its edges. Only the plane matters to the
  // horizon, not which way its normal points.
  vec3 face = cross(dFdx(v_view_position), dFdy(v_view_position));
  float face_length = length(face);
  face = face_length > 1e-30 ? face / face_length : n;
  o_albedo = vec4(albedo.rgb, u_lit);
#ifndef NO_MATERIAL_TARGET
  float metallic, roughness, occlusion;
  vec3 emissive;
  surface_material(metallic, roughness, occlusion, emissive);
  o_material = uvec2(packUnorm4x8(vec4(roughness, metallic, occlusion, 0.0)), pack_rgb9e5(emissive));
#endif
  o_normal = vec4(octahedron_encode(n), octahedron_encode(face));
  o_linear_depth = -v_view_position.z;
#ifdef LIGHTFIELD_MODULES
  o_world_position = vec4(v_world_position, 1.0);
#endif
#ifdef MOTION
  o_motion = vec4(v_view_motion, 0.0);
#endif
}
