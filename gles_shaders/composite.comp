// Composite: simple lighting (ambient + one directional light in view space) times (1 - AO), or
// one of the debug views. Writes display-ready sRGB.
#include "common.glsl"
#include "shared_layout.glsl"

layout(local_size_x = SSAO_GROUP_SIZE, local_size_y = SSAO_GROUP_SIZE) in;

layout(std140, binding = BINDING_COMPOSITE_PARAMS) uniform CompositeBlock { CompositeParams composite; };
uniform highp sampler2D u_albedo;
uniform highp sampler2D u_normal;
uniform highp sampler2D u_linear_depth;
uniform highp sampler2D u_ao;
layout(rgba8, binding = 0) writeonly uniform highp image2D u_output;

vec3 linear_to_srgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = composite.config.zw;
  if (pixel.x >= size.x || pixel.y >= size.y) return;
  float depth = texelFetch(u_linear_depth, pixel, 0).r;
  if (depth <= 0.0) {
    imageStore(u_output, pixel, vec4(linear_to_srgb(composite.background.rgb), 1.0));
    return;
  }
  float ao = composite.config.y != 0 ? texelFetch(u_ao, pixel, 0).r : 0.0;
  vec3 normal = texelFetch(u_normal, pixel, 0).xyz;
  vec3 result;
  int view = composite.config.x;
  if (view == VIEW_AO) {
    result = vec3(1.0 - ao);
  } else if (view == VIEW_NORMAL) {
    result = normal * 0.5 + 0.5;
    imageStore(u_output, pixel, vec4(result, 1.0));  // a data view: no sRGB encoding
    return;
  } else if (view == VIEW_DEPTH) {
    float t = (depth - composite.depth_range.x) / (composite.depth_range.y - composite.depth_range.x);
    imageStore(u_output, pixel, vec4(vec3(1.0 - clamp(t, 0.0, 1.0)), 1.0));
    return;
  } else {
    vec3 albedo = texelFetch(u_albedo, pixel, 0).rgb;
    float ambient = composite.light_direction.w;
    float diffuse = max(dot(normal, composite.light_direction.xyz), 0.0);
    result = albedo * (ambient + (1.0 - ambient) * diffuse) * (1.0 - ao);
  }
  imageStore(u_output, pixel, vec4(linear_to_srgb(result), 1.0));
}
