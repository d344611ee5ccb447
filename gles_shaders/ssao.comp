// SSAO with three estimators over one set of tables (ESTIMATOR selects at compile time):
//  ESTIMATOR_SPHERE:     Algorithm 1 of Doronin et al. (Mittring's CryEngine 2 method): samples in a
//                        sphere around the point, counted when hidden behind the stored surface.
//  ESTIMATOR_HEMISPHERE: the same test on cosine-weighted samples in the hemisphere about the normal.
//  ESTIMATOR_HORIZON:    horizon search per screen-space slice with the cosine-weighted arc integral
//                        of GTAO (Jimenez et al. 2016).
// Every radius gives its own AO; the radii merge by max (Hoang & Low). Large radii read coarser
// levels of the depth chain. Output: r = AO in [0,1], g = linear depth / far for the blur and upsample.
//
// LIGHTFIELD_MODULES: Algorithm 2 of Doronin et al. for one optical module of a light field display.
// The shaded point comes from the positions texture (world space), samples are placed around it in
// world space, and each is mapped to the module's image by its world-to-image transform
// (lightfield.glsl) and compared with the module's depth (distance from the observer line). The
// per-sample turn is seeded from the world position, so one surface point gets the same samples in
// every module. Sphere and hemisphere estimators; the horizon search walks screen-space slices and
// has no such form.
#include "common.glsl"
#include "shared_layout.glsl"
#include "gbuffer_normals.glsl"
#ifdef LIGHTFIELD_MODULES
#include "lightfield.glsl"
uniform highp sampler2D u_positions;  // world position of the visible surface; a = 0 on background
#endif

#ifndef ESTIMATOR
#define ESTIMATOR ESTIMATOR_SPHERE
#endif
#if defined(LIGHTFIELD_MODULES) && ESTIMATOR == ESTIMATOR_HORIZON
#error "the horizon estimator has no Algorithm 2 form; modules use sphere or hemisphere"
#endif

layout(local_size_x = SSAO_GROUP_SIZE, local_size_y = SSAO_GROUP_SIZE) in;

layout(std140, binding = BINDING_SSAO_PARAMS) uniform SsaoBlock { SsaoParams ssao; };
uniform highp sampler2D u_linear_depth;  // level 0 full resolution, then the depth chain
uniform highp sampler2D u_normal;        // view-space shading and face normals (gbuffer_normals.glsl)
uniform highp float u_inverse_far;
layout(rgba16f, binding = 0) writeonly uniform highp image2D u_ao;

const highp float kPi = 3.14159265358979;

highp float radius_at(int k) { return ssao.radii[k].x; }
int level_at(int k) { return ssao.levels[k].x; }
ivec2 full_size() { return ivec2(ssao.full_width, ssao.full_height); }

highp float depth_at(ivec2 texel, int level) {
  // Odd sizes round down level by level, so the last row or column maps past the coarse level's end.
  return texelFetch(u_linear_depth, min(texel >> level, textureSize(u_linear_depth, level) - 1), level).r;
}

highp vec3 view_position(ivec2 texel, highp float depth) {
  return view_position_at(texel, depth, ssao.unproject, full_size());
}

// Per-sample arithmetic runs at this precision; AO_MEDIUMP (--precision mediump) makes it fp16 as
// embedded GPUs run it.
#ifdef AO_MEDIUMP
#define SAMPLE_PRECISION mediump
#else
#define SAMPLE_PRECISION highp
#endif

#if ESTIMATOR != ESTIMATOR_HORIZON

#ifdef LIGHTFIELD_MODULES
// Algorithm 2, rows 3-9: the share of kernel points around the world position that the module's
// stored surface hides. Depths are distances from the observer line in physical units; the radius
// and bias are scaled to match (world to physical is a uniform scale).
highp float hidden_share_module(highp vec3 world, highp float depth, highp mat3 basis, highp float radius) {
  highp float physical_radius = radius * lightfield_module.physical_per_world;
  highp float bias = ssao.depth_bias * physical_radius;
  highp float pz = lightfield_module.module_z, d = lightfield_module.observer_distance;
  int hidden = 0;
  for (int i = 0; i < ssao.samples; ++i) {
    highp vec3 sample_world = world + radius * (basis * ssao.kernel[i].xyz);
    highp vec3 q = (lightfield_module.world_to_physical * vec4(sample_world, 1.0)).xyz;
    if (q.z <= pz || q.z >= d) continue;  // outside the module's image space: nothing can hide it
    highp vec2 ndc = module_ndc(module_screen_point(q));
    ivec2 texel = ivec2(floor((ndc * 0.5 + 0.5) * vec2(full_size())));
    if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, full_size()))) continue;
    highp float surface = texelFetch(u_linear_depth, texel, 0).r;
    highp float sample_depth = module_depth(q);
    if (surface > 0.0 && surface < sample_depth - bias && abs(surface - depth) < physical_radius) ++hidden;
  }
  return float(hidden) / float(ssao.samples);
}

// A turn per world cell (a fraction of the base radius across): the same in every module.
highp vec2 world_turn(highp vec3 world) {
  uvec3 cell = uvec3(ivec3(floor(world / lightfield_module.seed_cell)));
  uint h = cell.x * 0x8da6b343u ^ cell.y * 0xd8163841u ^ cell.z * 0xcb1ab31fu;
  h ^= h >> 16;
  h *= 0x7feb352du;
  h ^= h >> 15;
  highp float angle = float(h >> 8) * (6.28318530718 / 16777216.0);
  return vec2(cos(angle), sin(angle));
}
#endif

#if ESTIMATOR == ESTIMATOR_HEMISPHERE
// How far the shaded point's tangent plane lies from the eye along the ray through `ndc` (0 where the
// plane turns away from that ray).
highp float plane_depth(highp vec2 ndc, highp vec3 normal, highp float plane) {
  highp float facing = dot(normal, vec3((ndc + ssao.unproject.zw) * ssao.unproject.xy, -1.0));
  return facing < -1e-4 ? plane / facing : 0.0;
}

// The stored depth holds at a texel's centre; on a slanted face the depth changes within one texel by
// as much as a small radius, and samples just above the face would read as hidden (self-occlusion that
// grows as radii shrink towards a pixel). This moves the stored depth along the shaded point's tangent
// plane to the sample's exact position; on another surface it is off by that surface's own slope
// over a fraction of a texel, as before.
highp float subtexel_shift(highp vec2 ndc, ivec2 texel, int level, highp vec3 normal, highp float plane, highp float radius) {
  ivec2 coarse = min(texel >> level, textureSize(u_linear_depth, level) - 1);
  highp vec2 centre = (vec2(coarse) + 0.5) * float(1 << level) / vec2(full_size()) * 2.0 - 1.0;
  highp float exact = plane_depth(ndc, normal, plane), at_centre = plane_depth(centre, normal, plane);
  return exact > 0.0 && at_centre > 0.0 ? clamp(exact - at_centre, -radius, radius) : 0.0;
}
#endif

// The share of kernel points, placed by `basis` at `radius`, that the stored surface hides. A point
// counts when the surface is in front of it by more than the bias, and that surface lies within the
// radius of the shaded point in depth: farther occluders are other geometry (no halos).
// Everything per sample is relative to the shaded point (offsets, depth differences), so at mediump
// the small quantities keep their precision; only the pixel's own position and projection are highp.
highp float hidden_share(highp vec3 position, highp float depth, highp mat3 basis, highp float radius, int level) {
  SAMPLE_PRECISION float bias = ssao.depth_bias * radius;
  highp vec4 clip_centre = ssao.projection * vec4(position, 1.0);
#if ESTIMATOR == ESTIMATOR_HEMISPHERE
  highp float plane = dot(basis[2], position);
#endif
  int hidden = 0;
  for (int i = 0; i < ssao.samples; ++i) {
    SAMPLE_PRECISION vec3 offset = radius * (basis * ssao.kernel[i].xyz);
    highp vec4 clip = clip_centre + ssao.projection * vec4(offset, 0.0);
    if (clip.w <= 0.0) continue;  // behind the eye: nothing on screen can hide it
    highp vec2 ndc = clip.xy / clip.w;
    ivec2 texel = ivec2(floor((ndc * 0.5 + 0.5) * vec2(full_size())));
    if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, full_size()))) continue;
    highp float surface = depth_at(texel, level);
#if ESTIMATOR == ESTIMATOR_HEMISPHERE
    if (surface > 0.0) surface += subtexel_shift(ndc, texel, level, basis[2], plane, radius);
#endif
    SAMPLE_PRECISION float surface_offset = surface - depth;  // how far the surface lies behind the point
    SAMPLE_PRECISION float sample_offset = -offset.z;          // how far the sample lies behind it
    if (surface > 0.0 && surface_offset < sample_offset - bias && abs(surface_offset) < radius) ++hidden;
  }
  return float(hidden) / float(ssao.samples);
}
#else
// The cosine-weighted integral over a slice from the view vector to the horizon angle h, for the
// normal at angle gamma in the slice (GTAO's closed form).
highp float arc_integral(highp float h, highp float gamma, highp float cos_normal, highp float sin_gamma) {
  return (cos_normal + 2.0 * h * sin_gamma - cos(2.0 * h - gamma)) * 0.25;
}

// Taps from 1 to HORIZON_FADE_END radii away count less the farther they are: their elevation (as a
// pseudo-angle) shrinks linearly to nothing there (docs/ao.md, "The bias" and "AO in motion" hold the
// sweeps that chose 2.0).
#define HORIZON_FADE_END 2.0
// The nearest the first tap of each side comes to the point, in full-resolution pixels: the others
// are a quarter of the radius apart or more, and missed every crease and groove narrower than that
// (docs/ao.md, "AO in motion"). Not 1.5: along the axes that lands on a texel's edge, where float
// rounding picks the texel.
#define HORIZON_NEAR_TAP_PIXELS 1.6
// A tap's pseudo-angle is at most this times its share (see horizon_occlusion): it binds only past
// about pi - 0.1.
#define HORIZON_ELEVATION_CAP 20.0

// How far tap `step_index` of `steps` lies from the point, in pixels: the rest spaced equally to the
// radius, at least a pixel apart, each `jitter` of a step from the end of the step before (0.5: at
// the ends of the steps, the last at the radius), and the first `jitter` of the way from
// HORIZON_NEAR_TAP_PIXELS to half a step, where the second one's range begins. Accumulated frames
// move them all along the slice, so the AO converges on the horizon over every distance from the
// near one to the radius and not over a few fixed ones, which drew rings around every tall occluder
// (docs/ao.md, "AO in motion").
highp float tap_distance_pixels(int step_index, int steps, highp float radius_pixels, highp float jitter) {
  if (steps == 1) return radius_pixels;
  highp float spacing = radius_pixels / float(steps - 1);
  if (step_index == 0) return min(mix(HORIZON_NEAR_TAP_PIXELS, max(0.5 * spacing, HORIZON_NEAR_TAP_PIXELS), jitter), radius_pixels);
  return max((float(step_index) + jitter - 0.5) * spacing, float(step_index));
}

// GTAO for one radius: per slice, the highest horizon on each side (fading beyond the radius), then the
// visible arc integrated with the cosine to the normal projected into the slice.
// A tap's horizon is its elevation above the shaded point's tangent plane, the angle between the
// slice's tangent on its side and the tap: a tap rounded to its texel's centre lies up to half a
// texel off the slice, and on a plane that put it above the slice's own tangent line (a horizon
// measured from the view direction saw false occlusion on every face, the more the nearer the tap).
// The result is the occluded share of the slices' open arcs (a ratio), not 1 minus their mean
// visibility: one slice's open arc integrates to 1 only on average over slice angles, so with few
// slices 1 - mean visibility swings below 0 on tilted open faces and clamping that biased AO upwards
// (+0.09 with one slice, +0.03 with two, against the near-field reference).
highp float horizon_occlusion(ivec2 pixel, highp vec3 position, highp vec3 normal, highp vec3 face, highp float depth,
                              highp float turn_angle, highp float tap_jitter, highp float radius, int level) {
  highp float radius_pixels = radius * ssao.pixels_per_unit / depth;
  if (radius_pixels < 1.0) return 0.0;  // the radius falls inside this pixel: nothing to find
  int steps = ssao.horizon_steps;
  int slices = max(1, ssao.samples / (2 * steps));
  highp vec3 view = normalize(-position);
  // A tap's view position is (texel x tap_scale + tap_offset) x depth: view_position's arithmetic with
  // its divisions done once per pixel rather than per tap.
  highp vec2 tap_scale = 2.0 * ssao.unproject.xy / vec2(full_size());
  highp vec2 tap_offset = (1.0 / vec2(full_size()) - 1.0 + ssao.unproject.zw) * ssao.unproject.xy;
  highp float inverse_radius = 1.0 / radius;
  ivec2 last_texel = textureSize(u_linear_depth, level) - 1;  // depth_at's clamp, its size queried once
  highp float visibility = 0.0, open = 0.0;
  for (int slice = 0; slice < slices; ++slice) {
    // Slices repeat every pi / slices: the pixel's turn (a full circle over the tile) is spread over
    // that period, or the 4x4 tile would hold as few as two distinct slice directions. Evenly spaced:
    // each slice's turn covers only its own pi / slices, so slices offset by the pattern's points
    // (as they were) covered some directions twice over the frames and others never, and the
    // accumulated AO converged on an error that depended on those points (docs/ao.md, "AO in motion").
    highp float phi = (kPi * float(slice) + 0.5 * turn_angle) / float(slices);
    highp vec2 direction = vec2(cos(phi), sin(phi));
    highp vec3 direction_view = vec3(direction, 0.0);
    highp vec3 ortho = direction_view - dot(direction_view, view) * view;
    highp vec3 axis = normalize(cross(ortho, view));
    highp vec3 projected_normal = normal - axis * dot(normal, axis);
    highp float projected_length = length(projected_normal);
    if (projected_length < 1e-6) continue;  // the normal is the slice's axis: no arc to integrate
    highp float cos_normal = clamp(dot(projected_normal, view) / projected_length, -1.0, 1.0);
    highp float gamma = sign(dot(ortho, projected_normal)) * acos(cos_normal);
    // The slice's tangent towards the positive side; the normal's own component counts the rise, so a
    // tap off the slice but on the tangent plane rises by nothing.
    highp vec3 tangent_plus = cross(projected_normal, axis) / projected_length;
    // Elevations above the tangent, as pseudo-angles: 0 is the tangent plane, 2 (pi) the far tangent.
    // They start at the face's own plane: where the shading normal leans off the facet's, part of
    // its hemisphere lies below the facet, and a ray sent there leaves through the facet itself. No
    // tap finds that when the facet is narrower than the near tap's distance, and on a finely
    // tessellated mesh with smooth normals it is most of the AO that speckles from face to face
    // (armadillo's bias -0.0056 without it; docs/ao.md, "AO in motion"). The face's trace on the slice
    // rises above the tangent on one side (share as for a tap; the trace points along the tangent,
    // so no elevation passes the normal) and sinks on the other.
    highp vec3 face_trace = cross(axis, face);
    if (dot(face_trace, tangent_plus) < 0.0) face_trace = -face_trace;
    highp float face_along = dot(face_trace, tangent_plus) * projected_length;
    highp float face_rise = dot(face_trace, normal);
    highp float elevation_plus = face_rise > 0.0 ? face_rise / (face_along + face_rise) : 0.0;
    highp float elevation_minus = face_rise < 0.0 ? -face_rise / (face_along - face_rise) : 0.0;
    for (int step_index = 0; step_index < steps; ++step_index) {
      highp float distance_pixels = tap_distance_pixels(step_index, steps, radius_pixels, tap_jitter);
      for (int side = 0; side < 2; ++side) {
        highp vec2 offset = (side == 0 ? 1.0 : -1.0) * distance_pixels * direction;
        ivec2 texel = pixel + ivec2(floor(offset + 0.5));
        if (any(lessThan(texel, ivec2(0))) || any(greaterThanEqual(texel, full_size()))) continue;
        highp float sample_depth = texelFetch(u_linear_depth, min(texel >> level, last_texel), level).r;
        if (sample_depth <= 0.0) continue;
        // Per tap, everything is relative to the shaded point and in units of the radius. All of it
        // stays highp, at mediump too: at fp16 these offsets and the elevation below moved the AO by
        // up to 0.0015 on llvmpipe, which evaluates part of its mediump arithmetic at 16 bits (the near
        // tap's offset is a few hundredths of the radius, its rise a small difference of such numbers).
        highp vec3 delta = (vec3((vec2(texel) * tap_scale + tap_offset) * sample_depth, -sample_depth) - position) * inverse_radius;
        highp float distance = length(delta);
        if (distance >= HORIZON_FADE_END || distance <= 0.0) continue;
        // The elevation is the angle of (along, rise / projected_length); both are scaled by
        // projected_length to stay within the reach.
        highp float rise = dot(delta, normal);
        if (rise <= 0.0) continue;  // on or below the tangent plane: hides nothing
        highp float along = dot(delta, tangent_plus) * (side == 0 ? projected_length : -projected_length);
        // As a pseudo-angle, which orders taps as their angles do without trigonometry per tap (an atan
        // per tap made the AO pass half as slow again on llvmpipe): share = rise / (|along| + rise) is
        // 0 on the tangent plane and 1 along the normal; past the normal the pseudo-angle is 2 - share,
        // up to 2 at the far tangent (pi). A tap within rounding of the tangent plane but behind the
        // point (off the slice on a face seen edge-on) would jump from 0 to 2 on the sign of its rise:
        // the cap keeps it continuous in the rise, and binds only within about 0.1 rad of pi.
        highp float share = rise / (abs(along) + rise);
        highp float elevation = min(along >= 0.0 ? share : 2.0 - share, HORIZON_ELEVATION_CAP * share);
        // A surface seen beyond the radius is the front of what may reach within it (the hidden
        // underside of a ball above the floor): it counts, fading to nothing at HORIZON_FADE_END
        // radii. Cutting it off at the radius made the AO too light (docs/ao.md, "The bias").
        if (distance > 1.0) elevation *= (HORIZON_FADE_END - distance) / (HORIZON_FADE_END - 1.0);
        if (side == 0) elevation_plus = max(elevation_plus, elevation);
        else elevation_minus = max(elevation_minus, elevation);
      }
    }
    // Back from pseudo-angles to radians: (1 - p, min(p, 2 - p)) points the way the tap did.
    elevation_plus = atan(min(elevation_plus, 2.0 - elevation_plus), 1.0 - elevation_plus);
    elevation_minus = atan(min(elevation_minus, 2.0 - elevation_minus), 1.0 - elevation_minus);
    // Horizon angles from the view direction. A visible tap never lies past it; where the normal
    // leans past it too (smooth normals at a silhouette), the side's arc is empty whatever the taps.
    highp float h1 = gamma + 0.5 * kPi - min(elevation_plus, max(gamma + 0.5 * kPi, 0.0));
    highp float h0 = gamma - 0.5 * kPi + min(elevation_minus, max(0.5 * kPi - gamma, 0.0));
    highp float sin_gamma = sin(gamma);
    visibility += projected_length * (arc_integral(h0, gamma, cos_normal, sin_gamma) + arc_integral(h1, gamma, cos_normal, sin_gamma));
    // The whole open arc, arc_integral from gamma - pi/2 to gamma + pi/2, in closed form.
    open += projected_length * (cos_normal + gamma * sin_gamma);
  }
  return open > 0.0 ? clamp(1.0 - visibility / open, 0.0, 1.0) : 0.0;
}
#endif

void main() {
  ivec2 ao_pixel = ivec2(gl_GlobalInvocationID.xy);
  if (ao_pixel.x >= ssao.ao_width || ao_pixel.y >= ssao.ao_height) return;
  // At reduced resolution each AO pixel shades the first full-resolution pixel of its block.
  ivec2 pixel = ao_pixel << ssao.ao_shift;
  highp float depth = texelFetch(u_linear_depth, pixel, 0).r;
  bool background = depth <= 0.0;
  if (background) {  // nothing to occlude: the pixel, and a group of nothing but background, ends here
    if (ssao.shade_background == 0) {
      imageStore(u_ao, ao_pixel, vec4(0.0));
      return;
    }
    depth = 1.0 / u_inverse_far;  // measuring the skip: do the work a surface at the far plane would cost
  }
#ifdef LIGHTFIELD_MODULES
  // Algorithm 2, rows 1-2: the world position from the positions texture, not from depth.
  highp vec3 position = texelFetch(u_positions, pixel, 0).xyz;
  highp vec2 turn = lightfield_module.pixel_turns == 1
      ? ssao.rotation[(pixel.y % SSAO_ROTATION_TILE) * SSAO_ROTATION_TILE + pixel.x % SSAO_ROTATION_TILE].xy
      : world_turn(position);
#else
  highp vec3 position = view_position(pixel, depth);
  highp vec4 tile_entry = ssao.rotation[(pixel.y % SSAO_ROTATION_TILE) * SSAO_ROTATION_TILE + pixel.x % SSAO_ROTATION_TILE];
  highp vec2 turn = tile_entry.xy;
#endif
#if ESTIMATOR == ESTIMATOR_SPHERE
  highp mat3 basis = mat3(turn.x, turn.y, 0.0, -turn.y, turn.x, 0.0, 0.0, 0.0, 1.0);
#elif ESTIMATOR == ESTIMATOR_HEMISPHERE
  highp vec3 normal = background ? vec3(0.0, 0.0, 1.0) : shading_normal(texelFetch(u_normal, pixel, 0));
  highp vec3 reference = vec3(turn, 0.0);
  highp vec3 tangent = reference - normal * dot(reference, normal);
  // The turn lies in the image plane; a normal in that plane along the turn needs another tangent.
  if (dot(tangent, tangent) < 1e-6) tangent = vec3(-turn.y, turn.x, 0.0) - normal * dot(vec3(-turn.y, turn.x, 0.0), normal);
  tangent = normalize(tangent);
  highp mat3 basis = mat3(tangent, cross(normal, tangent), normal);
#else
  highp vec4 normals = texelFetch(u_normal, pixel, 0);
  highp vec3 normal = background ? vec3(0.0, 0.0, 1.0) : shading_normal(normals);
  highp vec3 face = background ? normal : face_normal(normals);
  highp float turn_angle = atan(turn.y, turn.x);
  highp float tap_jitter = tile_entry.z;
#endif
  float ao = ssao.skipped_radii_ao;
  for (int k = ssao.first_radius; k < ssao.end_radius; ++k) {
#if ESTIMATOR == ESTIMATOR_HORIZON
    ao = max(ao, horizon_occlusion(pixel, position, normal, face, depth, turn_angle, tap_jitter, radius_at(k), level_at(k)));
#elif defined(LIGHTFIELD_MODULES)
    ao = max(ao, hidden_share_module(position, depth, basis, radius_at(k)));
#else
    ao = max(ao, hidden_share(position, depth, basis, radius_at(k), level_at(k)));
#endif
  }
  imageStore(u_ao, ao_pixel, background ? vec4(0.0) : vec4(ao, depth * u_inverse_far, 0.0, 0.0));
}
