// The G-buffer's normal target (rgba16f) holds two view-space unit normals, each as a point on the
// octahedron (Cigolle et al. 2014): rg the shading normal, ba the geometric normal of the face the
// pixel lies on. The horizon estimator needs the face: with smooth normals the shading hemisphere
// dips below a facet's plane, and a ray sent there leaves through the facet itself, as the
// ray-traced reference finds (docs/ao.md, "AO in motion"). Two normals in the target's four channels
// cost no bandwidth over one stored as xyz; half floats hold the octahedron's coordinates to within
// 2^-11, about 0.06 degrees.
#ifndef GBUFFER_NORMALS_GLSL
#define GBUFFER_NORMALS_GLSL

highp vec2 sign_not_zero(highp vec2 v) { return vec2(v.x >= 0.0 ? 1.0 : -1.0, v.y >= 0.0 ? 1.0 : -1.0); }

highp vec2 octahedron_encode(highp vec3 n) {
  highp vec2 p = n.xy / (abs(n.x) + abs(n.y) + abs(n.z));
  return n.z >= 0.0 ? p : (1.0 - abs(p.yx)) * sign_not_zero(p);
}

highp vec3 octahedron_decode(highp vec2 p) {
  highp vec3 n = vec3(p, 1.0 - abs(p.x) - abs(p.y));
  if (n.z < 0.0) n.xy = (1.0 - abs(n.yx)) * sign_not_zero(n.xy);
  return normalize(n);
}

// A cleared texel (background) decodes to +z, facing the camera.
highp vec3 shading_normal(highp vec4 texel) { return octahedron_decode(texel.xy); }
highp vec3 face_normal(highp vec4 texel) { return octahedron_decode(texel.zw); }

#endif
