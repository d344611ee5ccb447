// One level of the linear-depth chain: each texel is the mean of the non-background texels of the
// 2x2 block below it (0 when all four are background), so coarse levels keep object depths.
#include "common.glsl"
#include "shared_layout.glsl"

layout(local_size_x = SSAO_GROUP_SIZE, local_size_y = SSAO_GROUP_SIZE) in;

uniform highp sampler2D u_linear_depth;
uniform int u_source_level;
layout(r32f, binding = 0) writeonly uniform highp image2D u_target;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 target_size = imageSize(u_target);
  if (texel.x >= target_size.x || texel.y >= target_size.y) return;
  ivec2 source_size = textureSize(u_linear_depth, u_source_level);
  highp float sum = 0.0;
  int count = 0;
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      ivec2 source = texel * 2 + ivec2(dx, dy);
      if (source.x >= source_size.x || source.y >= source_size.y) continue;
      highp float depth = texelFetch(u_linear_depth, source, u_source_level).r;
      if (depth > 0.0) {
        sum += depth;
        ++count;
      }
    }
  imageStore(u_target, texel, vec4(count > 0 ? sum / float(count) : 0.0));
}
