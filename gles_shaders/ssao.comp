// SSAO, Algorithm 1 of Doronin et al. (Mittring's CryEngine 2 method) in view space: rebuild the
// pixel's position from linear depth, place samples from the fixed kernel around it (turned by the
// pixel's entry of the rotation tile), project each, and count the samples hidden behind the stored
// surface within the range check. Each radius gives its own fraction; the radii merge by max
// (Hoang & Low). Output: r = AO in [0,1], g = linear depth / far for the depth-aware blur.
#include "common.glsl"
#include "shared_layout.glsl"

layout(local_size_x = SSAO_GROUP_SIZE, local_size_y = SSAO_GROUP_SIZE) in;

layout(std140, binding = BINDING_SSAO_PARAMS) uniform SsaoBlock { SsaoParams ssao; };
uniform highp sampler2D u_linear_depth;
uniform highp float u_inverse_far;
layout(rgba16f, binding = 0) writeonly uniform highp image2D u_ao;

float radius_at(int k) {
  return k < 4 ? ssao.radii_0_3[k] : ssao.radius_4_bias.x;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = ssao.counts.zw;
  if (pixel.x >= size.x || pixel.y >= size.y) return;
  highp float depth = texelFetch(u_linear_depth, pixel, 0).r;
  if (depth <= 0.0) {  // background: nothing to occlude
    imageStore(u_ao, pixel, vec4(0.0));
    return;
  }
  highp vec2 ndc = (vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0;
  highp vec3 position = vec3((ndc + ssao.unproject.zw) * depth * ssao.unproject.xy, -depth);
  vec2 turn = ssao.rotation[(pixel.y % SSAO_ROTATION_TILE) * SSAO_ROTATION_TILE + pixel.x % SSAO_ROTATION_TILE].xy;

  float ao = 0.0;
  for (int k = 0; k < ssao.counts.y; ++k) {
    highp float radius = radius_at(k);
    highp float bias = ssao.radius_4_bias.y * radius;
    int hidden = 0;
    for (int i = 0; i < ssao.counts.x; ++i) {
      vec3 o = ssao.kernel[i].xyz;
      highp vec3 offset = vec3(turn.x * o.x - turn.y * o.y, turn.y * o.x + turn.x * o.y, o.z);
      highp vec3 sample_position = position + radius * offset;
      highp vec4 clip = ssao.projection * vec4(sample_position, 1.0);
      if (clip.w <= 0.0) continue;  // behind the eye: nothing on screen can hide it
      highp vec2 uv = (clip.xy / clip.w * 0.5 + 0.5) * vec2(size);
      ivec2 texel = ivec2(floor(uv));
      if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, size))) continue;
      highp float surface = texelFetch(u_linear_depth, texel, 0).r;
      highp float sample_depth = -sample_position.z;
      // Hidden if the stored surface is in front of the sample. The range check compares that
      // surface with the shaded point, not with the sample: an occluder more than a radius away in
      // depth is other geometry (no dark halos round silhouettes), while on a floor seen at a
      // grazing angle the surface in front of a sample is still near the point and counts.
      if (surface > 0.0 && surface < sample_depth - bias && abs(depth - surface) < radius) ++hidden;
    }
    ao = max(ao, float(hidden) / float(ssao.counts.x));
  }
  imageStore(u_ao, pixel, vec4(ao, depth * u_inverse_far, 0.0, 0.0));
}
