#include "ssao/sampling.h"
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

TEST(Sampling, StratifiedKernelsAreBetterBalancedThanRandomOnes) {
  // The centre of mass of a 64-sample kernel: stratified patterns spread their points evenly, so
  // theirs sits near the origin; independent random points wander by about 0.9 / sqrt(64) = 0.11.
  // (Poisson disk spacing is checked by its minimum distance above; it does not stratify the mean.)
  for (Pattern pattern : {Pattern::jittered, Pattern::latin}) {
    glm::dvec3 mean(0.0);
    for (const glm::dvec3& p : ssao::make_kernel(pattern, 64)) mean += p / 64.0;
    EXPECT_LT(glm::length(mean), 0.08) << ssao::name(pattern);
  }
}

TEST(Tables, CompiledTablesAreTheGeneratorsOutput) {
  for (ssao::Estimator estimator : ssao::kEstimators)
    for (Pattern pattern : ssao::kPatterns) {
      for (int n = 1; n <= ssao::kMaxKernelSamples; n += 7) {
        const auto expected = ssao::make_kernel(estimator, pattern, n);
        const auto table = ssao::kernel(estimator, pattern, n);
        ASSERT_EQ(table.size(), expected.size());
        for (size_t i = 0; i < table.size(); ++i)
          for (int c = 0; c < 3; ++c) EXPECT_EQ(table[i][c], static_cast<float>(expected[i][c]));
      }
    }
  const auto angles = ssao::make_rotation_angles();
  ASSERT_EQ(ssao::rotation_angles().size(), angles.size());
  for (size_t i = 0; i < angles.size(); ++i) EXPECT_EQ(ssao::rotation_angles()[i], static_cast<float>(angles[i]));
  const auto scales = ssao::make_radius_scales();
  ASSERT_EQ(ssao::radius_scales().size(), scales.size());
  EXPECT_EQ(ssao::radius_scales()[0], 1.0f);
  for (size_t i = 1; i < scales.size(); ++i) EXPECT_LT(ssao::radius_scales()[i], ssao::radius_scales()[i - 1]);
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
  EXPECT_NEAR(mean_z, 2.0 / 3.0, 0.01);   // sd of z is 0.24: 4 standard errors of the mean is 0.007
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
