// Depth-aware upsampling of reduced-resolution AO, shared by the present pass and the read-back
// compute pass. Each full-resolution pixel interpolates bilinearly between the low-resolution
// texels around it that lie on its own surface (depth within UPSAMPLE_DEPTH_TOLERANCE of its own,
// relative), so AO is smooth along a surface and does not bleed across edges. Where none of them
// does (a sliver narrower than a texel), it takes the one whose depth is closest. Taking the
// closest one everywhere, as before, drew each 2x2 block in one value: steps along every edge.
// Among those on its surface, texels whose points lie off the pixel's tangent plane weigh less
// (below).
#ifndef UPSAMPLE_GLSL
#define UPSAMPLE_GLSL

// 5%: a floor seen at 10 degrees changes depth by about 1% between two texels at 1024x768, an edge
// between objects by far more.
#define UPSAMPLE_DEPTH_TOLERANCE 0.05

// `ao` is low resolution (r = AO), `ao_size` its size; `linear_depth` full resolution, times
// `inverse_far` in depth / far; `depth` is the pixel's linear depth / far, > 0 (background never
// reaches here). `plane`: xyz the pixel's view-space normal, w how far off its tangent plane,
// relative to its depth, a texel's point may lie before its weight falls by e beyond the closest
// texel's (ViewTargets::upsample_plane_tolerance; 0: weigh by depth alone); `unproject` and
// `full_size` place pixels as view_position_at does.
// The texels' depths come from `linear_depth` at the pixels they shaded, not from their g: rgba16f
// rounds a depth by up to 2^-11 of itself, a quarter of the plane tolerance, which weighed two texels
// of one flat face up to 1.6 times apart.
highp float upsampled_ao(highp sampler2D ao, highp sampler2D linear_depth, highp float inverse_far, ivec2 ao_size,
                         ivec2 pixel, highp float depth, highp vec4 plane, highp vec4 unproject, ivec2 full_size) {
  // Low-resolution texel i shaded full-resolution pixel 2i, so pixel p lies at p / 2 in texels: an
  // even pixel on its own texel, an odd one halfway to the next.
  ivec2 base = pixel >> 1;
  highp vec2 f = vec2(pixel & 1) * 0.5;
  // Where depth alone cannot tell (a crease, a groove's two walls, a curved surface), the texels whose
  // points lie closest to the pixel's tangent plane are its surface: weighing the others down keeps a
  // groove's dark floor off the wall beside it. A texel's point is its depth times its pixel's ray
  // (view_position_at), and its pixel lies `offset` pixels from this one, so its height over the
  // plane is (depth_t - depth) dot(ray, n) + depth_t (offset x ray_step) . n.xy: a few multiplies a
  // texel instead of unprojecting each. The present pass costs about 1.5 ms more at 1024x768 on
  // llvmpipe (14.9 against 13.4 ms, alternating runs), 0.2 of it the 32-bit depth fetches.
  highp vec3 ray = view_position_at(pixel, 1.0, unproject, full_size);
  highp float facing = dot(ray, plane.xyz);
  highp vec2 step_along_normal = 2.0 * unproject.xy / vec2(full_size) * plane.xy;
  // exp(-|height| / (plane.w depth)); the factor common to all four cancels in the weighted mean, so
  // the heights need no shift by the least. 0 turns the weights off.
  highp float sharpness = plane.w > 0.0 ? 1.0 / (plane.w * depth) : 0.0;
  highp float best_difference = 1e30, best_ao = 0.0;
  highp float weight_sum = 0.0, ao_sum = 0.0;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      // Every lane fetches, whatever its weight: with the fetch under the weight's divergent branch,
      // llvmpipe crashed inside the TCG guest (SEGV reading a wild address in its JIT code, in
      // vm.kms_play, kms_hotplug and board_play; never on the host), and fetching an in-range texel
      // it then ignores costs next to nothing.
      ivec2 texel = clamp(base + ivec2(dx, dy), ivec2(0), ao_size - 1);
      highp float value = texelFetch(ao, texel, 0).r;
      highp float texel_depth = texelFetch(linear_depth, texel << 1, 0).r * inverse_far;
      highp float weight = (dx == 0 ? 1.0 - f.x : f.x) * (dy == 0 ? 1.0 - f.y : f.y);
      if (weight <= 0.0 || texel_depth <= 0.0) continue;
      highp float difference = abs(texel_depth - depth);
      if (difference < best_difference) {
        best_difference = difference;
        best_ao = value;
      }
      if (difference <= UPSAMPLE_DEPTH_TOLERANCE * depth) {
        highp vec2 offset = vec2((texel << 1) - pixel);
        highp float height = (texel_depth - depth) * facing + texel_depth * dot(offset, step_along_normal);
        weight *= exp(-abs(height) * sharpness);
        weight_sum += weight;
        ao_sum += weight * value;
      }
    }
  return weight_sum > 0.0 ? ao_sum / weight_sum : best_ao;
}

#endif
