// One separable blur pass; the direction is a parameter so one shader serves both passes. Each
// work group blurs a run of BLUR_GROUP_SIZE pixels along the direction and first copies the run and
// its apron into shared memory, so every texel is fetched about once rather than 2 * radius + 1 times.
// BILATERAL weights each tap by depth similarity so AO does not bleed across depth edges. DENOISE
// (with BILATERAL) also weights it by how closely its normal agrees with the centre's, so AO does
// not bleed across creases either, where depth runs on smoothly.
#include "common.glsl"
#include "shared_layout.glsl"
#include "gbuffer_normals.glsl"

layout(local_size_x = BLUR_GROUP_SIZE, local_size_y = 1) in;

layout(std140, binding = BINDING_BLUR_PARAMS) uniform BlurBlock { BlurParams blur; };
uniform highp sampler2D u_source;  // r: AO, g: depth / far (0 for background)
#ifdef DENOISE
uniform highp sampler2D u_normal;  // full resolution, view space (gbuffer_normals.glsl)
shared mediump vec3 run_normal[BLUR_GROUP_SIZE + 2 * BLUR_MAX_RADIUS];
#endif
layout(rgba16f, binding = 0) writeonly uniform highp image2D u_target;

shared highp vec2 run[BLUR_GROUP_SIZE + 2 * BLUR_MAX_RADIUS];

void main() {
  ivec2 size = ivec2(blur.width, blur.height);
  bool vertical = blur.direction != 0;
  int length_along = vertical ? size.y : size.x;
  int line = int(gl_WorkGroupID.y);  // the row (horizontal pass) or column (vertical pass)
  int first = int(gl_WorkGroupID.x) * BLUR_GROUP_SIZE - blur.radius;
  int local = int(gl_LocalInvocationID.x);
  // Fill the run and its apron of `radius` texels each side; edges repeat the last texel, as the
  // clamped taps of a per-pixel blur would.
  for (int i = local; i < BLUR_GROUP_SIZE + 2 * blur.radius; i += BLUR_GROUP_SIZE) {
    int along = clamp(first + i, 0, length_along - 1);
    ivec2 texel = vertical ? ivec2(line, along) : ivec2(along, line);
    run[i] = texelFetch(u_source, texel, 0).rg;
#ifdef DENOISE
    run_normal[i] = shading_normal(texelFetch(u_normal, texel << blur.ao_shift, 0));
#endif
  }
  barrier();
  int along = int(gl_WorkGroupID.x) * BLUR_GROUP_SIZE + local;
  if (along >= length_along) return;
  ivec2 pixel = vertical ? ivec2(line, along) : ivec2(along, line);
  int centre_index = local + blur.radius;
  highp vec2 centre = run[centre_index];
  if (centre.y <= 0.0) {  // background stays empty
    imageStore(u_target, pixel, vec4(centre, 0.0, 0.0));
    return;
  }
  float sum = centre.x * blur.weights[0].x;
  float total = blur.weights[0].x;
  for (int i = 1; i <= blur.radius; ++i) {
    for (int side = -1; side <= 1; side += 2) {
      highp vec2 value = run[centre_index + side * i];
      float weight = blur.weights[i].x;
#ifdef BILATERAL
      float tolerance = blur.depth_tolerance * centre.y;
      float difference = (value.y - centre.y) / tolerance;
      weight *= value.y > 0.0 ? exp(-difference * difference) : 0.0;
#endif
#ifdef DENOISE
      // cos^8 by three squarings: pow() with the power in a uniform made the whole blur five times
      // slower on llvmpipe (33 ms against 6.6 ms for bilateral at 512x384).
      float agreement = max(dot(run_normal[centre_index], run_normal[centre_index + side * i]), 0.0);
      agreement *= agreement;
      agreement *= agreement;
      weight *= agreement * agreement;
#endif
      sum += value.x * weight;
      total += weight;
    }
  }
  imageStore(u_target, pixel, vec4(sum / total, centre.y, 0.0, 0.0));
}
