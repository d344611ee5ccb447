// The upsampled AO as the present pass computes it, written to a full-resolution image: only for
// read-back (tests, --dump); the frame itself upsamples inside the present pass.
#include "common.glsl"
#include "shared_layout.glsl"
#include "upsample.glsl"
#include "gbuffer_normals.glsl"

layout(local_size_x = SSAO_GROUP_SIZE, local_size_y = SSAO_GROUP_SIZE) in;

layout(std140, binding = BINDING_UPSAMPLE_PARAMS) uniform UpsampleBlock { UpsampleParams upsample; };
uniform highp sampler2D u_ao;            // low resolution: r = AO
uniform highp sampler2D u_linear_depth;  // full resolution
uniform highp sampler2D u_normal;        // full resolution, view space (gbuffer_normals.glsl)
layout(rgba16f, binding = 0) writeonly uniform highp image2D u_target;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= upsample.full_width || pixel.y >= upsample.full_height) return;
  highp float depth = texelFetch(u_linear_depth, pixel, 0).r * upsample.inverse_far;
  if (depth <= 0.0) {
    imageStore(u_target, pixel, vec4(0.0));
    return;
  }
  highp vec4 plane = vec4(shading_normal(texelFetch(u_normal, pixel, 0)), upsample.plane_tolerance);
  highp float ao = upsampled_ao(u_ao, u_linear_depth, upsample.inverse_far, ivec2(upsample.ao_width, upsample.ao_height), pixel, depth, plane,
                                upsample.unproject, ivec2(upsample.full_width, upsample.full_height));
  imageStore(u_target, pixel, vec4(ao, depth, 0.0, 0.0));
}
