// Constants and uniform-block layouts shared by the GLSL shaders and the C++ renderer: C++
// includes this file inside a namespace that maps vec4/ivec4/mat4 to GLM types. Blocks use only
// vec4, ivec4 and mat4 members so std140 and the C++ layout agree with no padding rules involved.
#ifndef SHARED_LAYOUT_GLSL
#define SHARED_LAYOUT_GLSL

#define SSAO_MAX_SAMPLES 64
#define SSAO_MAX_RADII 5
#define SSAO_ROTATION_TILE 4
#define SSAO_GROUP_SIZE 8
#define BLUR_MAX_RADIUS 8
#define BLUR_GROUP_SIZE 64

// Uniform block bindings.
#define BINDING_SSAO_PARAMS 0
#define BINDING_BLUR_PARAMS 1
#define BINDING_COMPOSITE_PARAMS 2
#define BINDING_UPSAMPLE_PARAMS 3
#define BINDING_MODULE_PARAMS 4
#define BINDING_TEMPORAL_PARAMS 5

// Temporal accumulation: while the camera moves, history is trusted for at most this many frames,
// so a surface sliding across the screen carries at most that much resampled past with it.
#define TEMPORAL_MOVING_FRAMES 8

// What the present pass shows: the shaded image or one of the debug outputs.
#define OUTPUT_COLOR 0
#define OUTPUT_AO 1
#define OUTPUT_NORMAL 2
#define OUTPUT_DEPTH 3

// Estimators (ESTIMATOR define of ssao.comp).
#define ESTIMATOR_SPHERE 0
#define ESTIMATOR_HEMISPHERE 1
#define ESTIMATOR_HORIZON 2

#define DEPTH_CHAIN_MAX_LEVELS 8

struct SsaoParams {
  mat4 projection;         // view space -> clip space
  vec4 unproject;          // (1/P00, 1/P11, P20, P21): rebuilds view position from linear depth
  vec4 radii_0_3;          // world-space radius of each resolution, largest first
  vec4 radius_4_bias;      // x: fifth radius; y: depth bias as a fraction of the radius;
                           // z: pixels per view-space unit at depth 1 (P11 * full height / 2);
                           // w: the AO of the radii skipped as sub-pixel (their known value)
  ivec4 counts;            // x: samples per radius, y: radii configured, z: AO width, w: AO height
  ivec4 lods_0_3;          // depth-chain level each radius reads (large radii read coarse levels)
  ivec4 config;            // x: level of radius 4, y: AO resolution shift (0 full, 1 half), z: full width, w: full height
  ivec4 radius_range;            // x: first radius used this frame, y: one past the last (radii skipped per frame);
                                 // z: 1 runs the estimator on background pixels too (only to measure the skip);
                                 // w: horizon taps on each side of a slice (slices = samples / (2 w))
  vec4 kernel[SSAO_MAX_SAMPLES];                             // see ssao::make_kernel
  vec4 rotation[SSAO_ROTATION_TILE * SSAO_ROTATION_TILE];    // xy: cos, sin of the pixel's turn; z: where along
                                                             // its step each horizon tap falls (0.5: the end)
};

struct BlurParams {
  vec4 weights[BLUR_MAX_RADIUS + 1];  // x: Gaussian weight at distance i
  ivec4 config;                       // x: radius, y: direction (0 horizontal, 1 vertical), z: width, w: height
  vec4 bilateral;                     // x: depth tolerance relative to the centre depth
  ivec4 source;                       // x: AO resolution shift (denoise reads normals at full resolution)
};

struct UpsampleParams {
  ivec4 config;           // x: full width, y: full height, z: AO width, w: AO height
  vec4 depth;             // x: 1 / far (the AO texture's g channel is depth / far); y: the plane
                          // tolerance of upsample.glsl (0: depth alone)
  vec4 unproject;         // the presented view's, as SsaoParams.unproject
};

struct CompositeParams {
  vec4 light_direction;   // view space, normalised; w: ambient share
  vec4 background;        // linear RGB of empty pixels
  vec4 depth_range;       // x: near, y: far (for the depth view); z: 1 / far; w: fade (brightness multiplier)
  ivec4 config;           // x: output (OUTPUT_*), y: apply AO (0/1), z: width, w: height
  ivec4 ao_config;        // x, y: AO width and height; z: AO resolution shift (0 full, 1 half);
                          // w: unused
  ivec4 viewport;         // x, y: the view's lower-left pixel in the framebuffer
  vec4 shading;           // x: AO strength, the power on 1 - AO in the shaded image (1: as computed);
                          // y: the plane tolerance of upsample.glsl (0: depth alone)
  vec4 unproject;         // as SsaoParams.unproject, for the upsampling's plane test
};

// Temporal accumulation of the AO (temporal.comp): the previous frame's accumulated AO is found by
// reprojecting each pixel's surface point through the previous view, which is exact for static
// geometry under a moving camera, and kept where depth and normal agree.
struct TemporalParams {
  mat4 current_to_previous;  // current view space -> previous view space
  mat4 previous_projection;  // previous view space -> previous clip space
  mat4 view_to_world;        // current view space -> world (normals are compared in world space)
  vec4 unproject;            // the current frame's, as SsaoParams.unproject
  vec4 depth;                // x: current far; y: previous far; z: depth tolerance relative to depth;
                             // w: least cosine between the normals of a kept history texel and the pixel
  ivec4 config;              // x: 1 when there is a history; y: frames averaged at most; z: AO resolution
                             // shift (0 full, 1 half); w: 1 when the view moved since the previous frame
  ivec4 size;                // x, y: AO width and height; z, w: full width and height
};

// One optical module of a light field display (lightfield/modules.h, Module): what the G-buffer's
// vertex stage and Algorithm 2's SSAO need to map physical points to the module's image.
struct ModuleParams {
  mat4 world_to_physical;  // affine: the ROI transform
  mat4 physical_to_world;
  vec4 module;             // x: P.x, y: P.z, z: D (observer distance), w: y_obs (observer height)
  vec4 screen;             // x, y: footprint x0, x1; z: screen height; w: physical units per world unit
  vec4 depth;              // x: z_front, y: z_back (the physical z range rasterised); z: 1 / (D - z_back); w: world seed cell
  ivec4 size;              // x, y: the module's image size; z: 1 turns samples by the pixel tile as
                           // Algorithm 1 does (only to measure what world seeding buys); w: unused
};

#endif
