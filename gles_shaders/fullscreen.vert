// One triangle that covers the viewport, from gl_VertexID alone (no vertex buffer).
// PRESENT_BOUNDS: instead, two triangles (gl_VertexID 0..5) over a rectangle of tiles that
// covered_bounds.comp found to hold surfaces, one instance per band of the view, its rectangle an
// attribute.
precision highp float;

#ifdef PRESENT_BOUNDS
layout(location = 0) in highp uvec4 a_bounds;  // in tiles: first column and row, one past the last
uniform highp vec2 u_tile_scale;               // 2 * tile size / viewport size, per axis
#endif

void main() {
#ifdef PRESENT_BOUNDS
  int v = gl_VertexID;  // (0,0) (1,0) (1,1), (0,0) (1,1) (0,1)
  vec2 corner = vec2(v == 1 || v == 2 || v == 4 ? 1.0 : 0.0, v == 2 || v == 4 || v == 5 ? 1.0 : 0.0);
  vec2 low = vec2(a_bounds.xy), high = vec2(a_bounds.zw);
  // No surface: every vertex at one point, a triangle of no area.
  if (any(lessThanEqual(a_bounds.zw, a_bounds.xy))) low = high = vec2(0.0);
  // An edge tile reaches past the viewport; the clip volume cuts it at the edge.
  gl_Position = vec4(mix(low, high, corner) * u_tile_scale - 1.0, 0.0, 1.0);
#else
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
#endif
}
