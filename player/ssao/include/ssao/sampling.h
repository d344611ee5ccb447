#pragma once
// Sample kernels of the paper's SSAO: directions on the unit sphere in cylindrical coordinates
// (Algorithm 3), radii uniform in volume within the shell [rmin, rmax] (Algorithm 4), with the
// (xi1, xi2) pairs drawn by one of four patterns. Pure math, no GL; the table generator runs it at
// build time and the player reads the generated tables (tables.h).
#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "ssao/names.h"

namespace ssao {

// What the kernel is for: the paper's sphere around the point (Mittring), a cosine-weighted
// hemisphere about the normal, or the slices and steps of a horizon search (GTAO).
enum class Estimator { sphere, hemisphere, horizon };
inline constexpr Estimator kEstimators[] = {Estimator::sphere, Estimator::hemisphere, Estimator::horizon};
inline constexpr names::Named<Estimator> kEstimatorNames[] = {
    {Estimator::sphere, "sphere"}, {Estimator::hemisphere, "hemisphere"}, {Estimator::horizon, "horizon"}};
std::string_view name(Estimator estimator);
std::optional<Estimator> parse_estimator(std::string_view text);

enum class Pattern { random, jittered, latin, poisson };
inline constexpr Pattern kPatterns[] = {Pattern::random, Pattern::jittered, Pattern::latin, Pattern::poisson};
inline constexpr names::Named<Pattern> kPatternNames[] = {
    {Pattern::random, "random"}, {Pattern::jittered, "jittered"}, {Pattern::latin, "latin"}, {Pattern::poisson, "poisson"}};
std::string_view name(Pattern pattern);
std::optional<Pattern> parse_pattern(std::string_view text);

// A small deterministic generator (splitmix64): the tables must not depend on the C++ library.
class Random {
 public:
  explicit Random(uint64_t seed) : state_(seed) {}
  uint64_t next();
  double uniform();  // [0, 1)
 private:
  uint64_t state_;
};

// n points of the square [-1, 1]^2 drawn by `pattern`.
std::vector<glm::dvec2> square_points(Pattern pattern, int n, uint64_t seed);

// Algorithm 3: (xi1, xi2) in [-1, 1]^2 to the unit sphere; z = xi1, phi = pi * xi2, r = sqrt(1 - z^2).
// The map preserves area (Archimedes), so uniform points in the square are uniform on the sphere.
glm::dvec3 sphere_point(glm::dvec2 xi);

// Algorithm 4: u in [0, 1) to a radius whose cube is uniform in [rmin^3, rmax^3].
double shell_radius(double u, double rmin, double rmax);

// The paper's shell: rmin = 0.8 R, rmax = R.
inline constexpr double kShellMin = 0.8;

// (xi1, xi2) in [-1, 1]^2 to a cosine-weighted direction about +Z (Malley: the uniform disc lifted).
glm::dvec3 cosine_hemisphere_point(glm::dvec2 xi);

// The kernel for `estimator` and `pattern` with n samples:
//  sphere:     points in the unit ball's shell [0.8, 1] (Algorithms 3 and 4);
//  hemisphere: cosine-weighted directions about +Z with shell radii, in the normal's frame;
//  horizon:    (u1, u2, 0) in [0, 1)^2: slice-angle and step jitter of each slice.
std::vector<glm::dvec3> make_kernel(Estimator estimator, Pattern pattern, int n);
inline std::vector<glm::dvec3> make_kernel(Pattern pattern, int n) {
  return make_kernel(Estimator::sphere, pattern, n);
}

// Per-pixel turns about the view axis, a 4x4 tile in Bayer order so neighbours differ most.
std::vector<double> make_rotation_angles();

// Radii of the multi-resolution SSAO as fractions of the base radius, largest first.
std::vector<double> make_radius_scales();

}  // namespace ssao
