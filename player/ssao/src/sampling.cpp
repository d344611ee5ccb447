#include "ssao/sampling.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

#include "gles_shaders/shared_layout.h"

namespace ssao {

std::string_view name(Pattern pattern) {
  return names::name_of<Pattern>(kPatternNames, pattern);
}
std::string_view name(Estimator estimator) {
  return names::name_of<Estimator>(kEstimatorNames, estimator);
}
std::optional<Estimator> parse_estimator(std::string_view text) {
  return names::parse<Estimator>(kEstimatorNames, text);
}
std::optional<Pattern> parse_pattern(std::string_view text) {
  return names::parse<Pattern>(kPatternNames, text);
}

uint64_t Random::next() {
  uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double Random::uniform() {
  return static_cast<double>(next() >> 11) * 0x1.0p-53;
}

namespace {

std::vector<int> permutation(int n, Random& random) {
  std::vector<int> order(static_cast<size_t>(n));
  std::iota(order.begin(), order.end(), 0);
  for (int i = n - 1; i > 0; --i)  // Fisher-Yates with our own generator
    std::swap(order[static_cast<size_t>(i)], order[random.next() % static_cast<uint64_t>(i + 1)]);
  return order;
}

std::vector<glm::dvec2> unit_random(int n, Random& random) {
  std::vector<glm::dvec2> points;
  for (int i = 0; i < n; ++i) points.emplace_back(random.uniform(), random.uniform());
  return points;
}

// A rows x cols grid with one uniform point per cell; the most square factorisation of n.
std::vector<glm::dvec2> unit_jittered(int n, Random& random) {
  int rows = static_cast<int>(std::sqrt(static_cast<double>(n)));
  while (n % rows != 0) --rows;
  const int cols = n / rows;
  std::vector<glm::dvec2> points;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) points.emplace_back((c + random.uniform()) / cols, (r + random.uniform()) / rows);
  return points;
}

// N rooks: one point in every row and every column of an n x n grid.
std::vector<glm::dvec2> unit_latin(int n, Random& random) {
  const std::vector<int> column = permutation(n, random);
  std::vector<glm::dvec2> points;
  for (int i = 0; i < n; ++i)
    points.emplace_back((column[static_cast<size_t>(i)] + random.uniform()) / n, (i + random.uniform()) / n);
  return points;
}

// Bridson's algorithm in the unit square with minimum distance r.
std::vector<glm::dvec2> bridson(double r, Random& random) {
  constexpr int kTries = 30;
  const double cell = r / std::sqrt(2.0);
  const int grid = static_cast<int>(std::ceil(1.0 / cell));
  std::vector<int> occupant(static_cast<size_t>(grid * grid), -1);
  std::vector<glm::dvec2> points;
  std::vector<int> active;
  auto cell_of = [&](glm::dvec2 p) {
    return glm::ivec2(std::min(static_cast<int>(p.x / cell), grid - 1), std::min(static_cast<int>(p.y / cell), grid - 1));
  };
  auto add = [&](glm::dvec2 p) {
    const glm::ivec2 c = cell_of(p);
    occupant[static_cast<size_t>(c.y * grid + c.x)] = static_cast<int>(points.size());
    active.push_back(static_cast<int>(points.size()));
    points.push_back(p);
  };
  add({random.uniform(), random.uniform()});
  while (!active.empty()) {
    const size_t pick = random.next() % active.size();
    const glm::dvec2 base = points[static_cast<size_t>(active[pick])];
    bool placed = false;
    for (int t = 0; t < kTries && !placed; ++t) {
      const double angle = 2.0 * std::numbers::pi * random.uniform();
      const double distance = r * (1.0 + random.uniform());
      const glm::dvec2 p = base + distance * glm::dvec2(std::cos(angle), std::sin(angle));
      if (p.x < 0.0 || p.y < 0.0 || p.x >= 1.0 || p.y >= 1.0) continue;
      const glm::ivec2 c = cell_of(p);
      bool clear = true;
      for (int y = std::max(c.y - 2, 0); y <= std::min(c.y + 2, grid - 1) && clear; ++y)
        for (int x = std::max(c.x - 2, 0); x <= std::min(c.x + 2, grid - 1) && clear; ++x) {
          const int other = occupant[static_cast<size_t>(y * grid + x)];
          if (other >= 0 && glm::distance(points[static_cast<size_t>(other)], p) < r) clear = false;
        }
      if (clear) {
        add(p);
        placed = true;
      }
    }
    if (!placed) {
      active[pick] = active.back();
      active.pop_back();
    }
  }
  return points;
}

// Exactly n Poisson-disk points: shrink the disk until Bridson yields at least n, then drop the
// point with the closest neighbour until n remain, which keeps the minimum distance as large as it can.
std::vector<glm::dvec2> unit_poisson(int n, Random& random) {
  double r = 1.0;
  std::vector<glm::dvec2> points = bridson(r, random);
  while (static_cast<int>(points.size()) < n) {
    r *= 0.9;
    points = bridson(r, random);
  }
  while (static_cast<int>(points.size()) > n) {
    size_t worst = 0;
    double worst_distance = 1e9;
    for (size_t i = 0; i < points.size(); ++i)
      for (size_t j = 0; j < points.size(); ++j)
        if (i != j && glm::distance(points[i], points[j]) < worst_distance) {
          worst_distance = glm::distance(points[i], points[j]);
          worst = i;
        }
    points.erase(points.begin() + static_cast<std::ptrdiff_t>(worst));
  }
  return points;
}

}  // namespace

std::vector<glm::dvec2> square_points(Pattern pattern, int n, uint64_t seed) {
  Random random(seed);
  std::vector<glm::dvec2> unit;
  switch (pattern) {
    case Pattern::random:
      unit = unit_random(n, random);
      break;
    case Pattern::jittered:
      unit = unit_jittered(n, random);
      break;
    case Pattern::latin:
      unit = unit_latin(n, random);
      break;
    case Pattern::poisson:
      unit = unit_poisson(n, random);
      break;
  }
  for (glm::dvec2& p : unit) p = p * 2.0 - 1.0;
  return unit;
}

glm::dvec3 sphere_point(glm::dvec2 xi) {
  const double z = xi.x;
  const double phi = std::numbers::pi * xi.y;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

double shell_radius(double u, double rmin, double rmax) {
  const double t = rmin * rmin * rmin + u * (rmax * rmax * rmax - rmin * rmin * rmin);
  return std::cbrt(t);
}

glm::dvec3 cosine_hemisphere_point(glm::dvec2 xi) {
  const glm::dvec2 u = (xi + 1.0) * 0.5;
  const double r = std::sqrt(u.x);
  const double phi = 2.0 * std::numbers::pi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1.0 - u.x))};
}

std::vector<glm::dvec3> make_kernel(Estimator estimator, Pattern pattern, int n) {
  const uint64_t seed = 0x55A0'0000ull + static_cast<uint64_t>(n) * 16 + static_cast<uint64_t>(pattern);
  const std::vector<glm::dvec2> xi = square_points(pattern, n, seed);
  std::vector<glm::dvec3> kernel;
  if (estimator == Estimator::horizon) {
    for (const glm::dvec2& p : xi) kernel.emplace_back((p + 1.0) * 0.5, 0.0);
    return kernel;
  }
  // The radius variable is stratified (one sample per 1/n of the shell's volume, in shuffled
  // order) for every pattern but plain random, where it is random like the directions.
  Random random(seed ^ 0xFFFF'0000'0000ull);
  const std::vector<int> stratum = permutation(n, random);
  for (int i = 0; i < n; ++i) {
    const double u = pattern == Pattern::random ? random.uniform() : (stratum[static_cast<size_t>(i)] + random.uniform()) / n;
    const glm::dvec2 p = xi[static_cast<size_t>(i)];
    const glm::dvec3 direction = estimator == Estimator::sphere ? sphere_point(p) : cosine_hemisphere_point(p);
    kernel.push_back(shell_radius(u, kShellMin, 1.0) * direction);
  }
  return kernel;
}

std::vector<double> make_rotation_angles() {
  constexpr int kBayer[SSAO_ROTATION_TILE * SSAO_ROTATION_TILE] = {0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};
  std::vector<double> angles;
  for (int index : kBayer) angles.push_back(2.0 * std::numbers::pi * (index + 0.5) / 16.0);
  return angles;
}

std::vector<double> make_radius_scales() {
  std::vector<double> scales;
  for (int k = 0; k < SSAO_MAX_RADII; ++k) scales.push_back(std::ldexp(1.0, -k));
  return scales;
}

}  // namespace ssao
