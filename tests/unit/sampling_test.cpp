#include "ssao/sampling.h"
#include "ssao/params.h"
#include "ssao/reference.h"
#include "ssao/tables.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace {

using ssao::Pattern;

TEST(Sampling, Algorithm3MapsTheUniformSquareToTheUniformSphere) {
  // Moments of the uniform distribution on S^2: E[x] = E[y] = E[z] = 0, E[x^2] = E[y^2] = E[z^2] = 1/3.
  constexpr int n = 20000;
  const auto xi = ssao::square_points(Pattern::random, n, 7);
  glm::dvec3 mean(0.0), square(0.0);
  for (const glm::dvec2& p : xi) {
    const glm::dvec3 s = ssao::sphere_point(p);
    EXPECT_NEAR(glm::length(s), 1.0, 1e-12);
    mean += s / double(n);
    square += s * s / double(n);
  }
  // Standard error of a mean of n unit-variance-ish samples: sqrt(1/3 / n) ~ 0.004; allow 4 sigma.
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(mean[c], 0.0, 0.017) << "component " << c;
    EXPECT_NEAR(square[c], 1.0 / 3.0, 0.012) << "component " << c;
  }
}

TEST(Sampling, Algorithm4IsUniformInTheShellVolume) {
  EXPECT_DOUBLE_EQ(ssao::shell_radius(0.0, 0.8, 1.0), 0.8);
  EXPECT_DOUBLE_EQ(ssao::shell_radius(1.0, 0.8, 1.0), 1.0);
  // Half the shell's volume lies below the radius whose cube is the mean of the end cubes.
  EXPECT_NEAR(ssao::shell_radius(0.5, 0.8, 1.0), std::cbrt((0.512 + 1.0) / 2.0), 1e-15);
  // With rmin = 0 it is the ball: the radius of half the volume is 2^(-1/3).
  EXPECT_NEAR(ssao::shell_radius(0.5, 0.0, 1.0), std::pow(0.5, 1.0 / 3.0), 1e-15);
}

TEST(Sampling, JitteredPutsOnePointInEveryCell) {
  for (int n : {4, 6, 8, 9, 12, 16, 64}) {
    int rows = static_cast<int>(std::sqrt(double(n)));
    while (n % rows) --rows;
    const int cols = n / rows;
    std::set<std::pair<int, int>> cells;
    for (const glm::dvec2& p : ssao::square_points(Pattern::jittered, n, 3)) {
      ASSERT_GE(p.x, -1.0);
      ASSERT_LT(p.x, 1.0);
      cells.insert({static_cast<int>((p.x + 1) / 2 * cols), static_cast<int>((p.y + 1) / 2 * rows)});
    }
    EXPECT_EQ(static_cast<int>(cells.size()), n) << "n = " << n;
  }
}

TEST(Sampling, LatinSquareHasOnePointPerRowAndColumn) {
  for (int n : {5, 8, 13, 32}) {
    std::set<int> rows, cols;
    for (const glm::dvec2& p : ssao::square_points(Pattern::latin, n, 11)) {
      cols.insert(static_cast<int>((p.x + 1) / 2 * n));
      rows.insert(static_cast<int>((p.y + 1) / 2 * n));
    }
    EXPECT_EQ(static_cast<int>(rows.size()), n);
    EXPECT_EQ(static_cast<int>(cols.size()), n);
  }
}

double min_distance(const std::vector<glm::dvec2>& points) {
  double best = 1e9;
  for (size_t i = 0; i < points.size(); ++i)
    for (size_t j = i + 1; j < points.size(); ++j) best = std::min(best, glm::distance(points[i], points[j]));
  return best;
}

TEST(Sampling, PoissonDiskKeepsPointsApartAndHasExactlyN) {
  for (int n : {8, 16, 32}) {
    const auto poisson = ssao::square_points(Pattern::poisson, n, 5);
    ASSERT_EQ(static_cast<int>(poisson.size()), n);
    // Half the spacing of a square grid of n points over the side-2 square; random points come far closer.
    const double spacing = 2.0 / std::sqrt(double(n));
    EXPECT_GT(min_distance(poisson), 0.5 * spacing) << "n = " << n;
    EXPECT_LT(min_distance(ssao::square_points(Pattern::random, n, 5)), min_distance(poisson));
  }
}

TEST(Sampling, KernelsLieInTheShellAndAreDeterministic) {
  for (Pattern pattern : ssao::kPatterns) {
    for (int n : {1, 2, 7, 8, 16, 64}) {
      const auto kernel = ssao::make_kernel(pattern, n);
      ASSERT_EQ(static_cast<int>(kernel.size()), n);
      for (const glm::dvec3& p : kernel) {
        EXPECT_GE(glm::length(p), ssao::kShellMin - 1e-12);
        EXPECT_LE(glm::length(p), 1.0 + 1e-12);
      }
      EXPECT_EQ(kernel, ssao::make_kernel(pattern, n));
    }
  }
}

// The inverse of Algorithm 3 for a kernel point p = r (sqrt(1 - z^2) cos(pi xi2), sqrt(1 - z^2) sin(pi xi2), z):
// xi1 = z / r, xi2 = atan2(y, x) / pi, in [-1, 1]^2 (xi2 = +1 and -1 are the same direction).
glm::dvec2 xi_of(const glm::dvec3& p) {
  const double r = glm::length(p);
  return {p.z / r, std::atan2(p.y, p.x) / M_PI};
}

// Cell of x in [-1, 1] among `cells` equal cells; the top edge wraps to cell 0 (see xi_of).
int cell_of(double x, int cells) {
  const int c = static_cast<int>(std::floor((x + 1.0) / 2.0 * cells));
  return ((c % cells) + cells) % cells;
}

// Stratum of a kernel point's radius among n equal shares of the shell's volume: by Algorithm 4,
// t = r^3 is uniform in [rmin^3, rmax^3].
int radius_stratum(const glm::dvec3& p, int n) {
  const double rmin3 = ssao::kShellMin * ssao::kShellMin * ssao::kShellMin;
  const double t = std::pow(glm::length(p), 3.0);
  return std::clamp(static_cast<int>(std::floor((t - rmin3) / (1.0 - rmin3) * n)), 0, n - 1);
}

// The most square rows x cols grid of n cells (rows <= cols), as the jittered pattern lays it out.
std::pair<int, int> grid_of(int n) {
  int rows = static_cast<int>(std::sqrt(double(n)));
  while (n % rows) --rows;
  return {rows, n / rows};
}

// Occupied cells of the strata each stratified pattern promises, from the kernel alone.
struct Occupancy {
  size_t jittered_cells = 0, latin_rows = 0, latin_cols = 0, radius_strata = 0;
};
Occupancy occupancy(const std::vector<glm::dvec3>& kernel) {
  const int n = static_cast<int>(kernel.size());
  const auto [rows, cols] = grid_of(n);
  std::set<std::pair<int, int>> cells;
  std::set<int> latin_rows, latin_cols, strata;
  for (const glm::dvec3& p : kernel) {
    const glm::dvec2 xi = xi_of(p);
    cells.insert({cell_of(xi.x, cols), cell_of(xi.y, rows)});
    latin_cols.insert(cell_of(xi.x, n));
    latin_rows.insert(cell_of(xi.y, n));
    strata.insert(radius_stratum(p, n));
  }
  return {cells.size(), latin_rows.size(), latin_cols.size(), strata.size()};
}

TEST(Sampling, StratifiedKernelsPutOneSampleInEveryStratum) {
  // Read back from the kernel itself (Algorithm 3 inverted, Algorithm 4's volume fraction): a
  // jittered kernel has one sample in each of its rows x cols cells of the (xi1, xi2) square, a Latin
  // one one in every row and every column of the n x n grid, and every pattern but random one radius
  // in each of the n equal-volume shells. These hold by construction for every n.
  for (int n = 1; n <= ssao::kMaxKernelSamples; ++n) {
    const size_t all = static_cast<size_t>(n);
    const Occupancy jittered = occupancy(ssao::make_kernel(Pattern::jittered, n));
    EXPECT_EQ(jittered.jittered_cells, all) << "jittered, n = " << n;
    EXPECT_EQ(jittered.radius_strata, all) << "jittered, n = " << n;
    const Occupancy latin = occupancy(ssao::make_kernel(Pattern::latin, n));
    EXPECT_EQ(latin.latin_rows, all) << "latin, n = " << n;
    EXPECT_EQ(latin.latin_cols, all) << "latin, n = " << n;
    EXPECT_EQ(latin.radius_strata, all) << "latin, n = " << n;
    EXPECT_EQ(occupancy(ssao::make_kernel(Pattern::poisson, n)).radius_strata, all) << "poisson, n = " << n;
  }
  // The same checks tell an unstratified kernel apart: n independent uniform points fill n equally
  // likely cells with probability n!/n^n, 3.2e-27 for n = 64 (a scratch run of 200,000 random kernels
  // never did so for n = 16, where it is 1.1e-6; for n = 8 it measured 0.0024 against 8!/8^8 = 0.0024).
  const Occupancy random = occupancy(ssao::make_kernel(Pattern::random, 64));
  EXPECT_LT(random.jittered_cells, 64u);
  EXPECT_LT(random.latin_rows, 64u);
  EXPECT_LT(random.latin_cols, 64u);
  EXPECT_LT(random.radius_strata, 64u);
}

TEST(Sampling, HorizonKernelsAreTheirPatternInTheUnitSquare) {
  // The horizon kernel is the pattern's (u1, u2) in [0, 1)^2 itself, so the same strata show directly.
  for (int n : {5, 8, 12, 16, 37, 64}) {
    const auto [rows, cols] = grid_of(n);
    std::set<std::pair<int, int>> cells;
    std::set<int> latin_rows, latin_cols;
    for (const glm::dvec3& p : ssao::make_kernel(ssao::Estimator::horizon, Pattern::jittered, n)) {
      ASSERT_EQ(p.z, 0.0);
      cells.insert({static_cast<int>(p.x * cols), static_cast<int>(p.y * rows)});
    }
    for (const glm::dvec3& p : ssao::make_kernel(ssao::Estimator::horizon, Pattern::latin, n)) {
      latin_cols.insert(static_cast<int>(p.x * n));
      latin_rows.insert(static_cast<int>(p.y * n));
    }
    EXPECT_EQ(cells.size(), static_cast<size_t>(n)) << "n = " << n;
    EXPECT_EQ(latin_rows.size(), static_cast<size_t>(n)) << "n = " << n;
    EXPECT_EQ(latin_cols.size(), static_cast<size_t>(n)) << "n = " << n;
  }
}

// Algorithm 3 of the paper as written there: z = xi1, phi = pi xi2, r = sqrt(1 - z^2), x = r cos phi, y = r sin phi.
glm::dvec3 algorithm3(double xi1, double xi2) {
  const double z = xi1, phi = M_PI * xi2, r = std::sqrt(1.0 - z * z);
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Malley's method: a uniform point of the unit disc (polar, radius sqrt(u1)) lifted onto the hemisphere.
glm::dvec3 malley(double u1, double u2) {
  const glm::dvec2 disc = std::sqrt(u1) * glm::dvec2(std::cos(2.0 * M_PI * u2), std::sin(2.0 * M_PI * u2));
  return {disc.x, disc.y, std::sqrt(std::max(0.0, 1.0 - glm::dot(disc, disc)))};
}

TEST(Sampling, KernelsFollowTheirDefinitionsEntryByEntry) {
  // Every entry of every sphere and hemisphere kernel against the formulas, fed with the same
  // (xi1, xi2) the horizon kernel of that pattern and size holds (it is the pattern's point itself).
  // Algorithm 4 gives the radius as the cube root of a t uniform in [rmin^3, rmax^3]: its direction
  // part is checked per entry, its distribution over all kernels of the random pattern (each drawn
  // independently) by a Kolmogorov-Smirnov bound, and stratum by stratum in the test above.
  std::vector<double> random_t;
  const double rmin3 = ssao::kShellMin * ssao::kShellMin * ssao::kShellMin;
  for (Pattern pattern : ssao::kPatterns)
    for (int n = 1; n <= ssao::kMaxKernelSamples; ++n) {
      const auto horizon = ssao::make_kernel(ssao::Estimator::horizon, pattern, n);
      const auto sphere = ssao::make_kernel(ssao::Estimator::sphere, pattern, n);
      const auto hemisphere = ssao::make_kernel(ssao::Estimator::hemisphere, pattern, n);
      ASSERT_EQ(horizon.size(), static_cast<size_t>(n));
      ASSERT_EQ(sphere.size(), static_cast<size_t>(n));
      ASSERT_EQ(hemisphere.size(), static_cast<size_t>(n));
      for (size_t i = 0; i < sphere.size(); ++i) {
        const glm::dvec2 u(horizon[i].x, horizon[i].y);
        const glm::dvec2 xi = 2.0 * u - 1.0;
        const double r = glm::length(sphere[i]);
        EXPECT_GE(r, ssao::kShellMin - 1e-12) << ssao::name(pattern) << " n " << n << " i " << i;
        EXPECT_LE(r, 1.0 + 1e-12) << ssao::name(pattern) << " n " << n << " i " << i;
        const glm::dvec3 direction = algorithm3(xi.x, xi.y);
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(sphere[i][c], r * direction[c], 1e-12) << ssao::name(pattern) << " n " << n << " i " << i;
        const double hemisphere_r = glm::length(hemisphere[i]);
        EXPECT_GE(hemisphere_r, ssao::kShellMin - 1e-12);
        EXPECT_LE(hemisphere_r, 1.0 + 1e-12);
        const glm::dvec3 lifted = malley(u.x, u.y);
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(hemisphere[i][c], hemisphere_r * lifted[c], 1e-12) << ssao::name(pattern) << " n " << n << " i " << i;
        if (pattern == Pattern::random) random_t.push_back((std::pow(r, 3.0) - rmin3) / (1.0 - rmin3));
      }
    }
  // 2080 independent values: D exceeds 1.95 / sqrt(N) = 0.043 with probability 0.001 when they are
  // uniform. Radii linear in [rmin, rmax] instead of in volume give D = 0.055.
  std::sort(random_t.begin(), random_t.end());
  double d = 0.0;
  for (size_t i = 0; i < random_t.size(); ++i) {
    const double n = static_cast<double>(random_t.size());
    d = std::max({d, std::abs(random_t[i] - static_cast<double>(i) / n), std::abs(random_t[i] - static_cast<double>(i + 1) / n)});
  }
  EXPECT_LT(d, 1.95 / std::sqrt(static_cast<double>(random_t.size())));
}

TEST(Tables, CompiledTablesAreTheGeneratorsOutput) {
  // Every entry of every table: one wrong number anywhere must show.
  for (ssao::Estimator estimator : ssao::kEstimators)
    for (Pattern pattern : ssao::kPatterns) {
      for (int n = 1; n <= ssao::kMaxKernelSamples; ++n) {
        const auto expected = ssao::make_kernel(estimator, pattern, n);
        const auto table = ssao::kernel(estimator, pattern, n);
        ASSERT_EQ(table.size(), expected.size());
        for (size_t i = 0; i < table.size(); ++i)
          for (int c = 0; c < 3; ++c)
            ASSERT_EQ(table[i][c], static_cast<float>(expected[i][c]))
                << ssao::name(estimator) << ", " << ssao::name(pattern) << ", n " << n << ", sample " << i << ", component " << c;
      }
    }
  const auto angles = ssao::make_rotation_angles();
  ASSERT_EQ(ssao::rotation_angles().size(), angles.size());
  for (size_t i = 0; i < angles.size(); ++i) EXPECT_EQ(ssao::rotation_angles()[i], static_cast<float>(angles[i]));
  const auto scales = ssao::make_radius_scales();
  ASSERT_EQ(ssao::radius_scales().size(), scales.size());
  for (size_t i = 0; i < scales.size(); ++i) EXPECT_EQ(ssao::radius_scales()[i], static_cast<float>(scales[i])) << "radius " << i;
}

TEST(Tables, RadiusTableIsTheBaseRadiusHalvedFourTimes) {
  // The paper's multi-resolution SSAO uses 5 radii; ours are R, R/2, R/4, R/8, R/16 (docs/ao.md, "Tables").
  const auto scales = ssao::radius_scales();
  ASSERT_EQ(scales.size(), 5u);
  ASSERT_EQ(scales.size(), static_cast<size_t>(SSAO_MAX_RADII));
  for (size_t k = 0; k < scales.size(); ++k) EXPECT_EQ(scales[k], 1.0f / static_cast<float>(1 << k)) << "radius " << k;
}

// The n x n Bayer matrix by its recursive definition: B(2n) = [[4B, 4B + 2], [4B + 3, 4B + 1]].
std::vector<std::vector<int>> bayer(int n) {
  if (n == 1) return {{0}};
  const auto half = bayer(n / 2);
  std::vector<std::vector<int>> out(static_cast<size_t>(n), std::vector<int>(static_cast<size_t>(n)));
  const int offset[2][2] = {{0, 2}, {3, 1}};
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      out[static_cast<size_t>(y)][static_cast<size_t>(x)] =
          4 * half[static_cast<size_t>(y % (n / 2))][static_cast<size_t>(x % (n / 2))] + offset[y / (n / 2)][x / (n / 2)];
  return out;
}

TEST(Tables, RotationTileIsTheBayerMatrixOfSixteenthTurns) {
  // Entry (x, y) turns by the centre of sector B(y, x) of 16 equal sectors: 2 pi (B + 1/2) / 16.
  const auto matrix = bayer(SSAO_ROTATION_TILE);
  const auto angles = ssao::rotation_angles();
  ASSERT_EQ(angles.size(), static_cast<size_t>(SSAO_ROTATION_TILE * SSAO_ROTATION_TILE));
  for (int y = 0; y < SSAO_ROTATION_TILE; ++y)
    for (int x = 0; x < SSAO_ROTATION_TILE; ++x) {
      const double expected = 2.0 * M_PI * (matrix[static_cast<size_t>(y)][static_cast<size_t>(x)] + 0.5) / 16.0;
      EXPECT_NEAR(angles[static_cast<size_t>(y * SSAO_ROTATION_TILE + x)], expected, 1e-6) << x << ", " << y;
    }
}

// The blur's weights normalised over all 2 radius + 1 taps, which is what the passes apply (they
// divide by the sum of the weights they used): w_i = exp(-i^2 / (2 sigma^2)) / sum_{|j| <= radius} w_j.
std::vector<double> normalised_gaussian(double sigma, int radius) {
  std::vector<double> w;
  double sum = 0.0;
  for (int i = 0; i <= radius; ++i) {
    w.push_back(std::exp(-double(i * i) / (2.0 * sigma * sigma)));
    sum += (i == 0 ? 1.0 : 2.0) * w.back();
  }
  for (double& x : w) x /= sum;
  return w;
}

TEST(Blur, WeightsAreAGaussianOfTheStatedSigma) {
  // The block stores unnormalised weights (the passes normalise); compare shapes, normalised alike.
  for (float sigma : {0.5f, 1.0f, 2.0f, 3.7f})
    for (int radius : {1, 4, BLUR_MAX_RADIUS}) {
      ssao::BlurSettings settings;
      settings.sigma = sigma;
      settings.radius = radius;
      const auto params = ssao::pack_blur_params(settings, 0, 64, 32);
      EXPECT_EQ(params.radius, radius);
      EXPECT_EQ(params.direction, 0);
      EXPECT_EQ(params.width, 64);
      EXPECT_EQ(params.height, 32);
      const auto expected = normalised_gaussian(sigma, radius);
      double sum = 0.0;
      for (int i = 0; i <= radius; ++i) sum += (i == 0 ? 1.0 : 2.0) * params.weights[i].x;
      for (int i = 0; i <= radius; ++i)
        EXPECT_NEAR(params.weights[i].x / sum, expected[static_cast<size_t>(i)], 1e-6)
            << "sigma " << sigma << " radius " << radius << " tap " << i;
      for (int i = radius + 1; i <= BLUR_MAX_RADIUS; ++i) EXPECT_EQ(params.weights[i].x, 0.0f) << "beyond the radius, tap " << i;
    }
  // The paper's blur as this project configures it by default: radius 4, sigma 2 (docs/ao.md, "Blur").
  const ssao::BlurSettings defaults;
  EXPECT_EQ(defaults.radius, 4);
  EXPECT_EQ(defaults.sigma, 2.0f);
  ssao::BlurSettings too_wide;
  too_wide.radius = 3 * BLUR_MAX_RADIUS;
  EXPECT_EQ(ssao::pack_blur_params(too_wide, 1, 8, 8).radius, BLUR_MAX_RADIUS);
}

TEST(Blur, ReferenceBlurOfAnImpulseIsTheNormalisedGaussian) {
  // The CPU reference (which the GPU pass is compared with) spreads a single 1 into exactly the
  // normalised weights, in both directions. Its output is rounded to half floats (rgba16f): relative
  // error 2^-11, so allow 2^-10.
  for (int direction : {0, 1}) {
    ssao::BlurSettings settings;
    settings.sigma = 1.5f;
    settings.radius = 5;
    constexpr int kLength = 2 * 5 + 9;
    const int width = direction == 0 ? kLength : 3, height = direction == 0 ? 3 : kLength;
    const auto params = ssao::pack_blur_params(settings, direction, width, height);
    std::vector<ssao::AoTexel> image(static_cast<size_t>(width * height), ssao::AoTexel(0.0f, 0.5f));
    const glm::ivec2 centre(width / 2, height / 2);
    image[static_cast<size_t>(centre.y * width + centre.x)].x = 1.0f;
    for (bool bilateral : {false, true}) {  // equal depths: the bilateral blur is the Gaussian one
      const auto out = ssao::reference_blur(image, params, bilateral ? ssao::Blur::bilateral : ssao::Blur::gaussian);
      const auto expected = normalised_gaussian(settings.sigma, settings.radius);
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
          const glm::ivec2 offset = glm::ivec2(x, y) - centre;
          const int along = direction == 0 ? offset.x : offset.y, across = direction == 0 ? offset.y : offset.x;
          const double want =
              across == 0 && std::abs(along) <= settings.radius ? expected[static_cast<size_t>(std::abs(along))] : 0.0;
          EXPECT_NEAR(out[static_cast<size_t>(y * width + x)].x, want, want * 0x1p-10)
              << "direction " << direction << " bilateral " << bilateral << " pixel " << x << ", " << y;
          EXPECT_EQ(out[static_cast<size_t>(y * width + x)].y, 0.5f);
        }
    }
  }
}

TEST(Tables, RotationTileTurnsNeighboursApart) {
  const auto angles = ssao::rotation_angles();
  std::set<float> distinct(angles.begin(), angles.end());
  EXPECT_EQ(distinct.size(), angles.size());
  // Horizontal neighbours in the tile differ by at least an eighth of a turn.
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x + 1 < 4; ++x) {
      const double d = std::abs(angles[static_cast<size_t>(y * 4 + x)] - angles[static_cast<size_t>(y * 4 + x + 1)]);
      EXPECT_GE(std::min(d, 2 * M_PI - d), 2 * M_PI / 8 - 1e-6);
    }
}

TEST(Sampling, HemisphereKernelsAreCosineWeightedAboutZ) {
  // Cosine-weighted directions have E[z] = 2/3 and E[z^2] = 1/2; the kernel's points lie in the shell.
  const auto xi = ssao::square_points(Pattern::random, 20000, 9);
  double mean_z = 0.0, mean_z2 = 0.0;
  for (const glm::dvec2& p : xi) {
    const glm::dvec3 d = ssao::cosine_hemisphere_point(p);
    EXPECT_NEAR(glm::length(d), 1.0, 1e-12);
    ASSERT_GE(d.z, 0.0);
    mean_z += d.z / 20000.0;
    mean_z2 += d.z * d.z / 20000.0;
  }
  EXPECT_NEAR(mean_z, 2.0 / 3.0, 0.01);  // sd of z is 0.24: 4 standard errors of the mean is 0.007
  EXPECT_NEAR(mean_z2, 0.5, 0.01);
  for (const glm::dvec3& p : ssao::make_kernel(ssao::Estimator::hemisphere, Pattern::jittered, 16)) {
    EXPECT_GE(p.z, 0.0);
    EXPECT_GE(glm::length(p), ssao::kShellMin - 1e-12);
    EXPECT_LE(glm::length(p), 1.0 + 1e-12);
  }
  for (const glm::dvec3& p : ssao::make_kernel(ssao::Estimator::horizon, Pattern::latin, 16)) {
    EXPECT_GE(p.x, 0.0);
    EXPECT_LT(p.x, 1.0);
    EXPECT_GE(p.y, 0.0);
    EXPECT_LT(p.y, 1.0);
  }
}

TEST(Patterns, NamesRoundTrip) {
  for (ssao::Estimator estimator : ssao::kEstimators) EXPECT_EQ(ssao::parse_estimator(ssao::name(estimator)), estimator);
  for (Pattern pattern : ssao::kPatterns) EXPECT_EQ(ssao::parse_pattern(ssao::name(pattern)), pattern);
  EXPECT_FALSE(ssao::parse_pattern("halton").has_value());
}

}  // namespace
