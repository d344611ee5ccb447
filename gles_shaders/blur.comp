// One separable blur pass; the direction is a parameter so one shader serves both passes.
// BILATERAL weights each tap by depth similarity so AO does not bleed across depth edges.
#include "common.glsl"
#include "shared_layout.glsl"

layout(local_size_x = BLUR_GROUP_SIZE, local_size_y = 1) in;

layout(std140, binding = BINDING_BLUR_PARAMS) uniform BlurBlock { BlurParams blur; };
uniform highp sampler2D u_source;  // r: AO, g: depth / far (0 for background)
layout(rgba16f, binding = 0) writeonly uniform highp image2D u_target;

void main() {
  ivec2 size = blur.config.zw;
  ivec2 pixel = blur.config.y == 0 ? ivec2(gl_GlobalInvocationID.xy) : ivec2(gl_GlobalInvocationID.yx);
  if (pixel.x >= size.x || pixel.y >= size.y) return;
  vec4 centre = texelFetch(u_source, pixel, 0);
  if (centre.g <= 0.0) {  // background stays empty
    imageStore(u_target, pixel, centre);
    return;
  }
  ivec2 step_dir = blur.config.y == 0 ? ivec2(1, 0) : ivec2(0, 1);
  float sum = centre.r * blur.weights[0].x;
  float total = blur.weights[0].x;
  for (int i = 1; i <= blur.config.x; ++i) {
    for (int side = -1; side <= 1; side += 2) {
      ivec2 tap = clamp(pixel + side * i * step_dir, ivec2(0), size - 1);
      vec4 value = texelFetch(u_source, tap, 0);
      float weight = blur.weights[i].x;
#ifdef BILATERAL
      float tolerance = blur.bilateral.x * centre.g;
      float difference = (value.g - centre.g) / tolerance;
      weight *= value.g > 0.0 ? exp(-difference * difference) : 0.0;
#endif
      sum += value.r * weight;
      total += weight;
    }
  }
  imageStore(u_target, pixel, vec4(sum / total, centre.g, 0.0, 0.0));
}
