#pragma once
// Converged, ray-traced AO at exactly the surface points of a View. Two references, each the value
// an estimator approximates:
//   near_field: the fraction of cosine-weighted directions in the normal hemisphere whose ray hits
//               geometry within radius R (obscurance with a step falloff, the usual AO reference).
//   sphere:     for each radius R_k, the fraction of points uniform in volume in the shell
//               [0.8 R_k, R_k] around the surface point that are hidden from the eye (the segment
//               eye -> point is blocked before the point: inside solid geometry or behind the
//               visible surface); radii merged by max. This is what the player's sphere estimator
//               (Mittring, the paper's Algorithms 1, 3, 4) approximates, without its depth bias and
//               range check and with the depth buffer replaced by the true geometry.
#include "aoref/dump.h"
#include "aoref/image.h"
#include "aoref/ray_scene.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace aoref {

enum class Reference { near_field, sphere };
std::string_view name(Reference reference);  // "near-field", "sphere"
std::optional<Reference> parse_reference(std::string_view text);

struct ReferenceSettings {
  Reference reference = Reference::sphere;
  int rays = 512;       // per pixel; for `sphere` per pixel and per radius. 1 .. 1 << 20
  double radius = 0.0;  // near_field only: 0 takes the view's largest radius
  uint64_t seed = 1;    // with the pixel index, seeds each pixel's sample shift: runs are reproducible
  int threads = 0;      // 0: one per hardware thread
  // Called on the calling thread about ten times a second and once at the end: rows done, rows.
  std::function<void(int, int)> progress;
};

struct ReferenceResult {
  Image ao;              // 1 channel, same size and orientation as the view, 0 on background
  Image standard_error;  // 1 channel: binomial sqrt(p (1 - p) / N) per pixel, 0 on background
  // sphere: the hidden fraction for each radius of view.radii (same order), so any prefix of the
  // radii can be merged by max without tracing again. near_field: one image, equal to `ao`.
  std::vector<Image> per_radius;
  double max_standard_error = 0.0, mean_standard_error = 0.0;  // over object pixels
  size_t object_pixels = 0;                                    // traced: object pixels with a usable normal
  uint64_t rays_traced = 0;
};

// The offset along the normal that keeps a near-field ray from hitting its own surface: 1e-5 of the
// scene's radius plus 1e-6 of the point's largest coordinate. Dumped positions are rebuilt from a
// 32-bit linear depth and stored as float, so they sit off the true surface by a few float steps of
// their magnitude (1.2e-7 relative each); this is about 10 such steps, and a ten-thousandth of the
// player's default radius (a tenth of the scene's radius), so it hides no real occluder.
double surface_epsilon(double scene_radius, const glm::dvec3& point);

// Returns false and says why (bad settings or view) in `error`; nothing is traced then.
bool compute_reference(const RayScene& scene, const View& view, const ReferenceSettings& settings, ReferenceResult& out,
                       std::string& error);

}  // namespace aoref
