// Temporal accumulation: each frame's AO turns its samples by a new angle (ssao::advance_frame), so
// the average over frames is an estimate with many times the samples. The previous frame's average
// is found by reprojecting the pixel's surface point into the previous view (exact for static
// geometry under a moving camera), read bilinearly from the texels whose depth and normal agree with
// the point, and blended with the new AO with weight 1 / frames. Where no texel agrees (a
// disocclusion, the screen's edge, a first frame) the history starts again from this frame.
// Output: r = the average, g = depth / far (as ssao.comp writes it, for the blur and upsample),
// b = the frames it averages; the world normal goes to a second image for the next frame's test.
// MOTION (an animated scene): the G-buffer's motion target says how far each pixel's surface point
// moved in this view's space since the previous frame's pose (gbuffer.vert); the point is moved back
// by it before the camera's reprojection, so a walking figure finds its own history, not the wall's
// behind it. While anything moves, every pixel trusts its history for TEMPORAL_MOVING_FRAMES at most
// (`moved`), the still ones too: a still floor's AO changes as a figure walks over it, and only a
// short history lets its contact shadow follow.
// The average is kept in 32-bit floats: in rgba16f a history of 64 frames stops moving once the new
// frame's share, (AO - average) / 64, falls under half a step of the stored value (3e-4 near 0.6),
// and the still camera's average came out up to 0.01 off the mean of its frames.
#include "common.glsl"
#include "shared_layout.glsl"
#include "gbuffer_normals.glsl"

// A moving part's pixels average 2 frames at most, and a history is clipped to this frame's
// neighbourhood mean within one deviation: measured with `aobench --ghosting` (docs/ao.md, AO of
// moving parts) on CesiumMan and Fox at 256x192, the error over moving pixels against the converged
// AO was 2.03 times one frame's with 8 frames, 1.52 with 4, 1.01 with 2 (0.5 deviations: no better).
#define MOVING_PART_FRAMES 2
#define CLIP_DEVIATIONS 1.0

layout(local_size_x = SSAO_GROUP_SIZE, local_size_y = SSAO_GROUP_SIZE) in;

layout(std140, binding = BINDING_TEMPORAL_PARAMS) uniform TemporalBlock { TemporalParams temporal; };
uniform highp sampler2D u_current;         // this frame's AO: r = AO, g = depth / far (0 on background)
uniform highp sampler2D u_normal;          // full resolution, view space (gbuffer_normals.glsl)
uniform highp sampler2D u_history;         // the previous frame's output of this pass
uniform highp sampler2D u_history_normal;  // xyz: world normal of each history texel
#ifdef MOTION
uniform highp sampler2D u_motion;  // xyz: the point's previous view position minus its current one
#endif
layout(rgba32f, binding = 0) writeonly uniform highp image2D u_target;
layout(rgba8_snorm, binding = 1) writeonly uniform highp image2D u_target_normal;

void main() {
  ivec2 ao_pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 ao_size = ivec2(temporal.ao_width, temporal.ao_height);
  ivec2 full_size = ivec2(temporal.full_width, temporal.full_height);
  if (ao_pixel.x >= ao_size.x || ao_pixel.y >= ao_size.y) return;
  highp vec2 current = texelFetch(u_current, ao_pixel, 0).rg;
  if (current.g <= 0.0) {  // background: nothing to remember
    imageStore(u_target, ao_pixel, vec4(0.0));
    imageStore(u_target_normal, ao_pixel, vec4(0.0));
    return;
  }
  // The AO pixel shaded the first full-resolution pixel of its block (ssao.comp).
  ivec2 pixel = ao_pixel << temporal.ao_shift;
  highp float depth = current.g * temporal.far_plane;
  highp vec3 position = view_position_at(pixel, depth, temporal.unproject, full_size);
  highp vec3 normal = normalize(mat3(temporal.view_to_world) * shading_normal(texelFetch(u_normal, pixel, 0)));
  highp float limit = float(temporal.moved != 0 ? min(temporal.max_frames, TEMPORAL_MOVING_FRAMES) : temporal.max_frames);
#ifdef MOTION
  highp vec3 motion = texelFetch(u_motion, pixel, 0).xyz;
  position += motion;
  if (dot(motion, motion) > 1e-6 * depth * depth) limit = min(limit, float(MOVING_PART_FRAMES));
#endif

  highp float history = 0.0, frames = 0.0, weight_sum = 0.0;
  if (temporal.has_history != 0) {
    highp vec3 previous = (temporal.current_to_previous * vec4(position, 1.0)).xyz;
    highp vec4 clip = temporal.previous_projection * vec4(previous, 1.0);
    highp float expected = -previous.z;  // the point's linear depth in the previous view
    if (clip.w > 0.0 && expected > 0.0) {
      highp vec2 previous_pixel = (clip.xy / clip.w * 0.5 + 0.5) * vec2(full_size);
      // AO texel i holds full-resolution pixel (i << shift), whose centre is at (i << shift) + 0.5.
      highp vec2 coordinate = (previous_pixel - 0.5) / float(1 << temporal.ao_shift);
      ivec2 base = ivec2(floor(coordinate));
      highp vec2 f = coordinate - vec2(base);
      highp float tolerance = temporal.depth_tolerance * expected;
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          ivec2 texel = base + ivec2(dx, dy);
          if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, ao_size))) continue;
          highp vec4 past = texelFetch(u_history, texel, 0);
          if (past.g <= 0.0) continue;  // background then
          if (abs(past.g * temporal.previous_far - expected) > tolerance) continue;  // another surface then
          if (dot(texelFetch(u_history_normal, texel, 0).xyz, normal) < temporal.normal_cosine) continue;
          highp float w = (dx == 0 ? 1.0 - f.x : f.x) * (dy == 0 ? 1.0 - f.y : f.y);
          history += w * past.r;
          frames += w * past.b;
          weight_sum += w;
        }
    }
  }
  highp float average = current.r;
  highp float count = 1.0;
  // A history that only a sliver of the footprint supports is as likely a neighbour's as this point's.
  if (weight_sum > 0.25) {
    history /= weight_sum;
#ifdef MOTION
    // While parts move, the AO of a point changes as they pass it, and a history of the point's
    // past AO lags behind: it is clipped to this frame's neighbourhood, its mean within one
    // standard deviation (variance clipping, Salvi 2016), as temporal anti-aliasing clips colour.
    if (temporal.moved != 0) {
      highp float sum = 0.0, sum_squares = 0.0, count_near = 0.0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          highp vec2 near = texelFetch(u_current, clamp(ao_pixel + ivec2(dx, dy), ivec2(0), ao_size - 1), 0).rg;
          if (near.g <= 0.0) continue;
          sum += near.r;
          sum_squares += near.r * near.r;
          count_near += 1.0;
        }
      highp float mean = sum / count_near;
      highp float deviation = sqrt(max(sum_squares / count_near - mean * mean, 0.0));
      history = clamp(history, mean - CLIP_DEVIATIONS * deviation, mean + CLIP_DEVIATIONS * deviation);
    }
#endif
    count = min(floor(frames / weight_sum + 0.5) + 1.0, limit);
    average = mix(history, current.r, 1.0 / count);
  }
  imageStore(u_target, ao_pixel, vec4(average, current.g, count, 0.0));
  imageStore(u_target_normal, ao_pixel, vec4(normal, 0.0));
}
