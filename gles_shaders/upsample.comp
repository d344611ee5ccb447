// Depth-aware upsampling of reduced-resolution AO: each full-resolution pixel takes the AO of the
// nearby low-resolution texel whose depth is closest to its own, so AO does not bleed across edges.
#include "common.glsl"
#include "shared_layout.glsl"

layout(local_size_x = SSAO_GROUP_SIZE, local_size_y = SSAO_GROUP_SIZE) in;

layout(std140, binding = BINDING_UPSAMPLE_PARAMS) uniform UpsampleBlock { UpsampleParams upsample; };
uniform highp sampler2D u_ao;            // low resolution: r = AO, g = depth / far
uniform highp sampler2D u_linear_depth;  // full resolution
layout(rgba16f, binding = 0) writeonly uniform highp image2D u_target;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= upsample.config.x || pixel.y >= upsample.config.y) return;
  highp float depth = texelFetch(u_linear_depth, pixel, 0).r * upsample.depth.x;
  if (depth <= 0.0) {
    imageStore(u_target, pixel, vec4(0.0));
    return;
  }
  // Low-resolution texel i shaded full-resolution pixel 2i; the candidates are the 2x2 texels whose
  // pixels surround this one: its own block and the neighbours on the side the pixel lies towards.
  ivec2 base = pixel >> 1;
  ivec2 toward = ivec2((pixel.x & 1) == 1 ? 1 : -1, (pixel.y & 1) == 1 ? 1 : -1);
  highp float best_difference = 1e30;
  highp float best_ao = 0.0;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      ivec2 texel = clamp(base + ivec2(dx, dy) * toward, ivec2(0), upsample.config.zw - 1);
      highp vec4 value = texelFetch(u_ao, texel, 0);
      if (value.g <= 0.0) continue;
      highp float difference = abs(value.g - depth);
      if (difference < best_difference) {
        best_difference = difference;
        best_ao = value.r;
      }
    }
  imageStore(u_target, pixel, vec4(best_ao, depth, 0.0, 0.0));
}
