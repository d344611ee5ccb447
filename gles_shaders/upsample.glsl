// Depth-aware upsampling of reduced-resolution AO, shared by the present pass and the read-back
// compute pass: each full-resolution pixel takes the AO of the nearby low-resolution texel whose
// depth is closest to its own, so AO does not bleed across edges.
#ifndef UPSAMPLE_GLSL
#define UPSAMPLE_GLSL

// `ao` is low resolution (r = AO, g = depth / far), `ao_size` its size; `depth` is the pixel's
// linear depth / far, > 0 (background never reaches here).
highp float upsampled_ao(highp sampler2D ao, ivec2 ao_size, ivec2 pixel, highp float depth) {
  // Low-resolution texel i shaded full-resolution pixel 2i; the candidates are the 2x2 texels whose
  // pixels surround this one: its own block and the neighbours on the side the pixel lies towards.
  ivec2 base = pixel >> 1;
  ivec2 toward = ivec2((pixel.x & 1) == 1 ? 1 : -1, (pixel.y & 1) == 1 ? 1 : -1);
  highp float best_difference = 1e30;
  highp float best_ao = 0.0;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      ivec2 texel = clamp(base + ivec2(dx, dy) * toward, ivec2(0), ao_size - 1);
      highp vec4 value = texelFetch(ao, texel, 0);
      if (value.g <= 0.0) continue;
      highp float difference = abs(value.g - depth);
      if (difference < best_difference) {
        best_difference = difference;
        best_ao = value.r;
      }
    }
  return best_ao;
}

#endif
