// Constants and uniform-block layouts shared by the GLSL shaders and the C++ renderer: C++
// includes this file inside a namespace that maps the GLSL types to GLM and int32/float/uint32, so
// each block is one named struct on both sides (ssao::pack_*_params and render::pack_*_params fill
// them). std140 and C++ agree only where no padding rule is involved, so blocks hold
//  - float, int and uint in runs of four (four scalars fill 16 bytes in both), padded with an
//    `unused_*` member where a run falls short;
//  - vec4, ivec4 and mat4, and arrays of them (std140 strides every array element by 16 bytes, so
//    an array of scalars is an array of vec4 whose x holds the value);
//  - int 0/1 for flags (a GLSL bool is 4 bytes, a C++ bool 1);
// and no vec2 or vec3 (std140 aligns them to 8 and 16 bytes, C++ to 4). The build checks every
// member's offset against glslangValidator's std140 reflection (layout_check.cmake).
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
#define BINDING_LIGHT_PARAMS 6

// The file's own lights (KHR_lights_punctual) the present pass shades; scene::kMaxLights alike.
#define MAX_LIGHTS 8

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
  mat4 projection;                  // view space -> clip space
  vec4 unproject;                   // (1/P00, 1/P11, P20, P21): view_position_at (common.glsl) rebuilds a
                                    // view position from linear depth with it
  vec4 radii[SSAO_MAX_RADII];       // x: world-space radius k, largest first
  ivec4 levels[SSAO_MAX_RADII];     // x: the depth-chain level radius k reads (large radii read coarse levels)
  int samples;                      // per radius (horizon: taps per pixel)
  int radius_count;                 // radii configured
  int first_radius;                 // the radii used this frame: first_radius up to end_radius (the others
  int end_radius;                   // are skipped this frame, see ssao::update_for_frame)
  int ao_width;                     // the AO image's size
  int ao_height;
  int full_width;                   // the view's size (the depth and normal textures')
  int full_height;
  int ao_shift;                     // AO resolution shift from full (0 full, 1 half)
  int horizon_steps;                // horizon taps on each side of a slice (slices = samples / (2 steps))
  int shade_background;             // 1 runs the estimator on background pixels too (only to measure the skip)
  int unused_0;
  float depth_bias;                 // as a fraction of the radius
  float pixels_per_unit;            // pixels per view-space unit at depth 1 (P11 * full_height / 2)
  float skipped_radii_ao;           // the AO of the radii skipped as sub-pixel (their known value)
  float unused_1;
  vec4 kernel[SSAO_MAX_SAMPLES];                             // see ssao::make_kernel
  vec4 rotation[SSAO_ROTATION_TILE * SSAO_ROTATION_TILE];    // xy: cos, sin of the pixel's turn; z: where along
                                                             // its step each horizon tap falls (0.5: the end)
};

struct BlurParams {
  vec4 weights[BLUR_MAX_RADIUS + 1];  // x: Gaussian weight at distance i
  int radius;                         // taps each side
  int direction;                      // 0 horizontal, 1 vertical
  int width;                          // the AO image's size
  int height;
  int ao_shift;                       // AO resolution shift (denoise reads normals at full resolution)
  float depth_tolerance;              // bilateral: relative to the centre depth
  int unused_0;
  int unused_1;
};

struct UpsampleParams {
  int full_width;          // the view's size
  int full_height;
  int ao_width;            // the AO image's size
  int ao_height;
  float inverse_far;       // 1 / far (the AO texture's g channel is depth / far)
  float plane_tolerance;   // of upsample.glsl (0: depth alone)
  float unused_0;
  float unused_1;
  vec4 unproject;          // the presented view's, as SsaoParams.unproject
};

struct CompositeParams {
  vec4 light_direction;    // xyz: view space, normalised: the key light, towards it
  vec4 light_color;        // rgb: the key light's irradiance (linear; 0: none)
  vec4 background;         // rgb: linear RGB of empty pixels
  vec4 unproject;          // as SsaoParams.unproject, for the upsampling's plane test and the view vector
  mat4 view_to_world;      // the environment is in world space
  vec4 irradiance[9];      // rgb: the environment's irradiance / pi as spherical harmonics (pbr.glsl)
  int apply_ao;            // 0/1
  int ao_shift;            // AO resolution shift (0 full: no upsampling, 1 half)
  int viewport_x;          // the view's lower-left pixel in the framebuffer
  int viewport_y;
  int full_width;          // the view's size
  int full_height;
  int ao_width;            // the AO image's size
  int ao_height;
  float near_plane;        // for the depth view
  float far_plane;
  float inverse_far;       // 1 / far_plane
  float fade;              // brightness multiplier (transitions between playlist items)
  float specular_max_level;     // the prefiltered cube map's last level (roughness 1)
  float ao_strength;            // the power on 1 - AO in the shaded image (1: as computed)
  float plane_tolerance;        // of upsample.glsl (0: depth alone)
  float environment_intensity;  // scales the environment's light
  int viewer_straight_ahead;    // 1: each pixel seen along +z (light field modules: the viewer on the
                                // observer line in front of it), 0: from the centre of projection
  int unused_0;
  int unused_1;
  int unused_2;
};

// The scene's own lights (scene::Light), in world space: the present pass shades in world space
// so a light field module, whose view space is physical space scaled from the world, sees the same
// falloff as a 2D view. Uploaded once per scene; count 0 leaves the key light of CompositeParams.
struct LightParams {
  vec4 color[MAX_LIGHTS];     // rgb: linear colour times intensity; a: 0 directional, 1 point or spot
  vec4 position[MAX_LIGHTS];  // xyz: the light's position, or (directional) the direction towards it;
                              // w: 1 / range^2 (0: unbounded)
  vec4 axis[MAX_LIGHTS];      // xyz: where a spot light shines (unit)
  vec4 cone[MAX_LIGHTS];      // x, y: glTF's angle scale and offset (1 / (cos inner - cos outer),
                              // -cos outer * scale); 0, 1 for a light without a cone
  int count;
  int unused_0;
  int unused_1;
  int unused_2;
};

// Temporal accumulation of the AO (temporal.comp): the previous frame's accumulated AO is found by
// reprojecting each pixel's surface point through the previous view, which is exact for static
// geometry under a moving camera, and kept where depth and normal agree.
struct TemporalParams {
  mat4 current_to_previous;  // current view space -> previous view space
  mat4 previous_projection;  // previous view space -> previous clip space
  mat4 view_to_world;        // current view space -> world (normals are compared in world space)
  vec4 unproject;            // the current frame's, as SsaoParams.unproject
  float far_plane;           // the current view's far
  float previous_far;        // the previous view's far
  float depth_tolerance;     // relative to depth
  float normal_cosine;       // least cosine between the normals of a kept history texel and the pixel
  int has_history;           // 1 when there is a history
  int max_frames;            // frames averaged at most
  int ao_shift;              // AO resolution shift (0 full, 1 half)
  int moved;                 // 1 when the view moved since the previous frame
  int ao_width;              // the AO image's size
  int ao_height;
  int full_width;            // the view's size
  int full_height;
};

// One optical module of a light field display (lightfield/modules.h, Module): what the G-buffer's
// vertex stage and Algorithm 2's SSAO need to map physical points to the module's image.
struct ModuleParams {
  mat4 world_to_physical;    // affine: the ROI transform
  mat4 physical_to_world;
  float module_x;            // P.x: the module's position
  float module_z;            // P.z
  float observer_distance;   // D
  float observer_height;     // y_obs
  float footprint_x0;        // the module's footprint on the screen, left to right
  float footprint_x1;
  float screen_height;
  float physical_per_world;  // the ROI's scale
  float z_front;             // the physical z range rasterised
  float z_back;
  float seed_cell;           // the world cell Algorithm 2's turns are seeded from
  float unused_0;
  int width;                 // the module's image size
  int height;
  int pixel_turns;           // 1 turns samples by the pixel tile as Algorithm 1 does (only to measure
                             // what world seeding buys)
  int unused_1;
};

#endif
