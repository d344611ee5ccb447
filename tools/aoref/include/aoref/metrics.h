#pragma once
// Error of an AO estimate against a reference, over object pixels only (depth > 0): background
// is 0 in both by convention and would only dilute the figures.
#include "aoref/image.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace aoref {

struct MetricsSettings {
  int edge_distance = 3;    // pixels (Chebyshev distance) around a depth edge that count as "near the edge"
  double edge_jump = 0.05;  // a depth edge: neighbouring depths differ by more than this fraction of the nearer
  double ssim_sigma = 1.5;  // Gaussian window of SSIM (Wang et al. 2004), truncated at ssim_radius
  int ssim_radius = 5;      // 11 x 11 window
  int noise_radius = 2;     // the box blur of Metrics::noise: 5 x 5
};

struct Metrics {
  double mae = 0.0, rmse = 0.0;
  double bias = 0.0;      // mean of estimate - reference: the sign of a systematic error
  double ssim = 1.0;      // mean SSIM over object pixels, dynamic range 1 (AO is in [0, 1])
  double edge_mae = 0.0;  // MAE over object pixels within edge_distance of a depth edge; NaN when there are none
  // The error's high-frequency part: mean |e - box(e)| with e = estimate - reference and box the
  // mean of e over the object pixels of the noise_radius window (5 x 5). Per-pixel noise and dither
  // patterns show here; a smooth bias does not.
  double noise = 0.0;
  size_t pixels = 0;  // object pixels compared; with none, every figure is NaN
  size_t edge_pixels = 0;
};

// 1 for object pixels within settings.edge_distance of a depth edge, else 0. An edge pixel is an
// object pixel with a 4-neighbour that is background, or whose depth differs from its own by more
// than edge_jump times the smaller of the two (a relative jump, so it means the same near and far).
std::vector<uint8_t> edge_mask(const Image& depth, const MetricsSettings& settings = {});

// Compares channel 0 of `estimate` with channel 0 of `reference` over the pixels where channel 0 of
// `depth` is > 0. SSIM's window only gathers object pixels, its Gaussian weights renormalised over
// them, so background next to a silhouette neither rewards nor penalises the estimate.
// Throws std::invalid_argument when the three images differ in size (a caller's mistake).
Metrics compare(const Image& estimate, const Image& reference, const Image& depth, const MetricsSettings& settings = {});

// Temporal stability. For each object pixel of frame t+1, the pixel of frame t that showed the same
// surface point: its world position (channels 0-2 of `position_now`, alpha in channel 3 > 0 on
// objects) projected by frame t's view-projection `view_projection_before` onto the nearest pixel,
// kept where frame t's position there lies within `tolerance` times the point's distance from
// `eye_before`. -1 where none does (disocclusion, off screen). Rows top-down as everywhere here.
std::vector<int64_t> match_previous(const Image& position_now, const Image& position_before,
                                    const glm::dmat4& view_projection_before, const glm::dvec3& eye_before,
                                    double tolerance = 0.01);
// Mean over matched pixels of |now - before at the match| (channel 0); NaN without a match.
double mean_change(const Image& now, const Image& before, const std::vector<int64_t>& match);

}  // namespace aoref
