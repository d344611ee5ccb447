// Moments of the direction samplers on S^3 against their closed forms. Each tolerance is five
// standard errors of the sample mean (sd / sqrt(N)), with the sd of the quantity worked out
// analytically beside it.
#include "ao4d/sampling.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <numbers>
#include <set>

namespace ao4d {
namespace {

constexpr int kSamples = 200000;
constexpr double kPi = std::numbers::pi;

double tolerance(double sd) {
  return 5.0 * sd / std::sqrt(static_cast<double>(kSamples));
}

TEST(UniformSphere, HasUnitLengthAndTheMomentsOfTheUniformDistributionOnS3) {
  Rng rng(1);
  double m1[4]{}, m2[4]{}, m4[4]{}, cross_xy = 0, cross_x2y2 = 0;
  for (int i = 0; i < kSamples; ++i) {
    const Vec4 d = uniform_sphere(rng);
    ASSERT_NEAR(length(d), 1.0, 1e-12);
    for (std::size_t a = 0; a < 4; ++a) {
      m1[a] += d[a];
      m2[a] += d[a] * d[a];
      m4[a] += std::pow(d[a], 4);
    }
    cross_xy += d.x * d.y;
    cross_x2y2 += d.x * d.x * d.w * d.w;
  }
  for (std::size_t a = 0; a < 4; ++a) {
    // On S^(n-1) in R^n: E[x] = 0 (sd 1/2), E[x^2] = 1/n (sd sqrt(1/8 - 1/16)), E[x^4] = 3/(n(n+2)).
    EXPECT_NEAR(m1[a] / kSamples, 0.0, tolerance(0.5)) << a;
    EXPECT_NEAR(m2[a] / kSamples, 0.25, tolerance(0.25)) << a;
    EXPECT_NEAR(m4[a] / kSamples, 1.0 / 8.0, tolerance(0.2)) << a;
  }
  EXPECT_NEAR(cross_xy / kSamples, 0.0, tolerance(0.21));
  EXPECT_NEAR(cross_x2y2 / kSamples, 1.0 / 24.0, tolerance(0.1));  // E[x^2 y^2] = 1/(n(n+2))
}

TEST(UniformHemisphere, StaysOnTheNormalsSideWithMeanCosine4Over3Pi) {
  Rng rng(2);
  const Vec4 n = normalize(Vec4{1, -2, 0.5, 3});
  double sum = 0;
  for (int i = 0; i < kSamples; ++i) {
    const double c = dot(uniform_hemisphere(rng, n), n);
    ASSERT_GE(c, 0.0);
    sum += c;
  }
  // E[cos] = Int cos / Int 1 over the hemisphere = (4 pi / 3) / pi^2. The same estimate times the
  // hemisphere's 3-volume pi^2 is the normalisation constant of the cosine-weighted density.
  EXPECT_NEAR(sum / kSamples, 4.0 / (3.0 * kPi), tolerance(0.3));
  EXPECT_NEAR(kPi * kPi * sum / kSamples, 4.0 * kPi / 3.0, kPi * kPi * tolerance(0.3));
}

TEST(CosineHemisphere, HasTheMomentsOfDensityCosOver4PiOver3) {
  for (const Vec4& n : {Vec4{1, 0, 0, 0}, Vec4{-1, 0, 0, 0}, normalize(Vec4{0.3, -0.2, 0.9, -0.1}), Vec4{0, 0, 0, -1}}) {
    Rng rng(3);
    double c1 = 0, c2 = 0, tangent = 0;
    for (int i = 0; i < kSamples; ++i) {
      const Vec4 d = cosine_hemisphere(rng, n);
      ASSERT_NEAR(length(d), 1.0, 1e-12);
      const double c = dot(d, n);
      ASSERT_GE(c, 0.0);
      c1 += c;
      c2 += c * c;
      tangent += length(d - c * n) > 0 ? dot(d - c * n, Vec4{1, 1, 1, 1}) : 0.0;
    }
    // Int_0^{pi/2} cos^k sin^2: k = 1: 1/3, k = 2: pi/16, k = 3: 2/15; so E[cos] = 3 pi / 16
    // and E[cos^2] = 2/5 under the density cos / (4 pi / 3).
    EXPECT_NEAR(c1 / kSamples, 3.0 * kPi / 16.0, tolerance(0.25));
    EXPECT_NEAR(c2 / kSamples, 0.4, tolerance(0.27));
    EXPECT_NEAR(tangent / kSamples, 0.0, tolerance(2.0));  // no preferred tangent direction
  }
}

TEST(PointSeed, DependsOnSeedStreamAndIndexOnly) {
  EXPECT_EQ(point_seed(1, SeedStream::voxels, 5), point_seed(1, SeedStream::voxels, 5));
  EXPECT_NE(point_seed(1, SeedStream::voxels, 5), point_seed(1, SeedStream::voxels, 6));
  EXPECT_NE(point_seed(1, SeedStream::voxels, 5), point_seed(2, SeedStream::voxels, 5));
  Rng a(point_seed(9, SeedStream::points, 3)), b(point_seed(9, SeedStream::points, 3));
  for (int i = 0; i < 10; ++i) EXPECT_EQ(a.next(), b.next());
}

// Voxel i and vertex i (and line i of a points file) of one run must not share their random
// directions: all seeds differ, and the streams' draws are uncorrelated.
TEST(PointSeed, StreamsOfVoxelsVerticesAndPointsAreIndependent) {
  constexpr std::uint64_t kCount = 20000;
  const SeedStream streams[] = {SeedStream::points, SeedStream::voxels, SeedStream::vertices};
  std::set<std::uint64_t> seeds;
  for (const SeedStream s : streams)
    for (std::uint64_t i = 0; i < kCount; ++i) seeds.insert(point_seed(1, s, i));
  EXPECT_EQ(seeds.size(), 3 * kCount);
  // Pearson correlation of the first uniform draw of point i in two streams; for independent
  // streams it is about normal with sd 1 / sqrt(kCount) = 0.007, so 4 sd is 0.028.
  for (std::size_t x = 0; x < 3; ++x)
    for (std::size_t y = x + 1; y < 3; ++y) {
      double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
      for (std::uint64_t i = 0; i < kCount; ++i) {
        const double u = Rng(point_seed(1, streams[x], i)).uniform(), v = Rng(point_seed(1, streams[y], i)).uniform();
        sx += u, sy += v, sxx += u * u, syy += v * v, sxy += u * v;
      }
      const double n = kCount;
      const double r = (sxy - sx * sy / n) / std::sqrt((sxx - sx * sx / n) * (syy - sy * sy / n));
      EXPECT_LT(std::abs(r), 4.0 / std::sqrt(n)) << "streams " << x << " and " << y;
    }
}

}  // namespace
}  // namespace ao4d
