#pragma once
// Settings of the AO passes and the uniform blocks they turn into. The renderer uploads these
// blocks and the CPU reference reads the same ones, so both run on identical inputs.
#include "gles_shaders/shared_layout.h"
#include "ssao/sampling.h"

#include <optional>
#include <string_view>

namespace ssao {

// What the SSAO pass's per-sample arithmetic runs at: highp (32 bits), or mediump, the AO_MEDIUMP
// variant of ssao.comp, fp16 where the GPU has it (as embedded GPUs run it; llvmpipe runs it at 32 bits).
enum class Precision { highp, mediump };
inline constexpr Precision kPrecisions[] = {Precision::highp, Precision::mediump};
inline constexpr names::Named<Precision> kPrecisionNames[] = {{Precision::highp, "highp"}, {Precision::mediump, "mediump"}};
std::string_view name(Precision precision);
std::optional<Precision> parse_precision(std::string_view text);

// The defaults are the configuration aobench put on the time-error front ahead of the paper's
// (sphere, 8 samples x 5 radii, Gaussian blur): see docs/ao.md, "Run time against error".
struct AoSettings {
  Estimator estimator = Estimator::horizon;
  Precision precision = Precision::highp;
  int samples = 30;  // per radius, 1..64 (horizon: taps per pixel, slices = samples / (2 steps))
  // Horizon: taps on each side of a slice, 1..32 (at most samples / 2): one 1.6 pixels from the point,
  // the rest spread evenly to the radius. The horizon is the highest of the taps, so too few of them
  // miss it and the AO comes out too light (docs/ao.md, "The bias"). Three slices of five: accumulation
  // over frames turns the slices, and no frame has taps to spare for a fourth (docs/ao.md, "AO in motion").
  int steps = 5;
  int radii = 1;  // 1..5, from the radius table, largest first
  Pattern pattern = Pattern::poisson;
  float bias = 0.03f;           // depth bias as a fraction of each radius
  bool half_resolution = true;  // AO at half width and height, then depth-aware upsampling
  // Large radii read coarser levels of the depth chain. Off by default: on llvmpipe, where it was
  // measured, building the chain costs more than the coarser reads save (docs/ao.md, "Run time against error").
  bool depth_chain = false;
  bool skip_radii = true;  // drop radii under a pixel or far beyond the scene, per frame
  // Background pixels return after one depth read (whole work groups of them at once). Off only to
  // measure what that saves (aobench's background=shade): the estimator then runs there as if a
  // surface stood at the far plane, and the result is still 0.
  bool skip_background = true;
};

// denoise: bilateral in depth and also in normals (edge-aware), so it keeps creases as well as silhouettes.
enum class Blur { off, gaussian, bilateral, denoise };
inline constexpr names::Named<Blur> kBlurNames[] = {
    {Blur::gaussian, "gaussian"}, {Blur::bilateral, "bilateral"}, {Blur::denoise, "denoise"}, {Blur::off, "off"}};
std::string_view name(Blur blur);
std::optional<Blur> parse_blur(std::string_view text);

struct BlurSettings {
  Blur mode = Blur::off;
  int radius = 4;                 // taps each side, 1..BLUR_MAX_RADIUS
  float sigma = 2.0f;             // Gaussian sigma in pixels
  float depth_tolerance = 0.05f;  // bilateral, denoise: depth difference, relative to depth, that halves trust
};

// The horizon estimator's taps on each side of a slice (`steps`, at most samples / 2); ssao.comp
// makes samples / (2 x steps) slices of them.
int horizon_steps(const AoSettings& settings);

// The SSAO block from the settings, with what no frame changes; `base_radius` is in world (= view)
// units; width and height are the full resolution (the AO resolution follows from
// settings.half_resolution). update_for_frame and advance_frame fill in the rest each frame.
shared_layout::SsaoParams pack_ssao_params(const AoSettings& settings, float base_radius, int width, int height);

// What the camera decides each frame: the projection, and from the scene's depth range which radii
// are worth computing (first_radius, end_radius, skipped_radii_ao) and which depth-chain level each
// one reads.
struct FrameView {
  glm::mat4 projection{1.0f};
  float nearest_depth = 1.0f;  // closest the scene's bounding sphere comes to the eye (>= near)
  float centre_depth = 1.0f;   // distance to the scene's centre
  float scene_radius = 1.0f;
};
void update_for_frame(shared_layout::SsaoParams& params, const AoSettings& settings, const FrameView& view);

// Turns the samples of frame `frame` of a sequence (temporal accumulation): every entry of the
// rotation tile turns by the frame's share of a whole circle, from a low-discrepancy sequence, so
// over frames every pixel sees every direction evenly instead of repeating the tile; and the
// horizon's taps move along their steps (rotation[i].z, 0.5 for the ends of the steps, which is where
// pack_ssao_params leaves them for a single frame) by the golden ratio's sequence, each entry from its own
// start, so over frames they cover the whole slice rather than a few fixed distances. The kernel
// never changes. The CPU reference reads the same block, so it follows.
void advance_frame(shared_layout::SsaoParams& params, unsigned frame);

// Levels of the depth chain for a full-resolution image (level 0 included).
int depth_chain_levels(int width, int height);
// The blur block of one pass. direction 0: horizontal, 1: vertical; width and height are the AO
// resolution's, `shift` its factor from the full resolution (0 or 1).
shared_layout::BlurParams pack_blur_params(const BlurSettings& settings, int direction, int width, int height, int shift = 0);

}  // namespace ssao
