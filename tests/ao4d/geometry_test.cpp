// Generalised cross product, cell normals and the ray-tetrahedron solver against a pivoted
// Gaussian elimination.
#include "ao4d/intersect.hpp"
#include "ao4d/mesh.hpp"
#include "ao4d/sampling.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <optional>
#include <utility>

namespace ao4d {
namespace {

Vec4 random_vec(Rng& rng) {
  return {rng.symmetric(), rng.symmetric(), rng.symmetric(), rng.symmetric()};
}

// Solves columns * x = rhs by Gaussian elimination with partial pivoting in long double.
std::optional<std::array<long double, 4>> solve4(const std::array<Vec4, 4>& columns, const Vec4& rhs) {
  long double m[4][5];
  for (std::size_t r = 0; r < 4; ++r) {
    for (std::size_t c = 0; c < 4; ++c) m[r][c] = columns[c][r];
    m[r][4] = rhs[r];
  }
  for (std::size_t c = 0; c < 4; ++c) {
    std::size_t pivot = c;
    for (std::size_t r = c + 1; r < 4; ++r)
      if (std::fabs(m[r][c]) > std::fabs(m[pivot][c])) pivot = r;
    if (m[pivot][c] == 0) return std::nullopt;
    for (std::size_t k = 0; k < 5; ++k) std::swap(m[c][k], m[pivot][k]);
    for (std::size_t r = c + 1; r < 4; ++r) {
      const long double f = m[r][c] / m[c][c];
      for (std::size_t k = c; k < 5; ++k) m[r][k] -= f * m[c][k];
    }
  }
  std::array<long double, 4> x{};
  for (std::size_t i = 4; i-- > 0;) {
    long double s = m[i][4];
    for (std::size_t k = i + 1; k < 4; ++k) s -= m[i][k] * x[k];
    x[i] = s / m[i][i];
  }
  return x;
}

// (t, l2, l3, l4) of O + t Dir = A + l2 e1 + l3 e2 + l4 e3 by brute force.
std::optional<std::array<long double, 4>> brute_force(const Vec4& o, const Vec4& dir, const std::array<Vec4, 4>& v) {
  return solve4({-dir, v[1] - v[0], v[2] - v[0], v[3] - v[0]}, o - v[0]);
}

TEST(CrossProduct, IsOrthogonalToItsArgumentsAndMatchesTheDeterminant) {
  Rng rng(7);
  for (int i = 0; i < 1000; ++i) {
    const Vec4 a = random_vec(rng), b = random_vec(rng), c = random_vec(rng), v = random_vec(rng);
    const Vec4 n = cross(a, b, c);
    const double scale = length(a) * length(b) * length(c);
    EXPECT_NEAR(dot(n, a), 0.0, 1e-14 * scale * length(a));
    EXPECT_NEAR(dot(n, b), 0.0, 1e-14 * scale * length(b));
    EXPECT_NEAR(dot(n, c), 0.0, 1e-14 * scale * length(c));
    // The defining property, and positive orientation of (n, a, b, c).
    EXPECT_NEAR(dot(n, v), det(v, a, b, c), 1e-13 * scale * length(v));
    EXPECT_GE(det(n, a, b, c), 0.0);
  }
}

TEST(CrossProduct, OfTheBasisFollowsTheAlternatingSigns) {
  const Vec4 ex{1, 0, 0, 0}, ey{0, 1, 0, 0}, ez{0, 0, 1, 0}, ew{0, 0, 0, 1};
  EXPECT_EQ(cross(ey, ez, ew), ex);
  EXPECT_EQ(cross(ex, ez, ew), -ey);  // the thesis's formula, without the sign, gives +ey here
  EXPECT_EQ(cross(ex, ey, ew), ez);
  EXPECT_EQ(cross(ex, ey, ez), -ew);
}

TEST(CellNormal, LengthIsSixTimesTheVolumeAndSwappingTwoVerticesFlipsIt) {
  TetMesh mesh;
  mesh.vertices = {{0, 0, 0, 0}, {2, 0, 0, 0}, {0, 3, 0, 0}, {0, 0, 4, 0}};
  mesh.cells = {{0, 1, 2, 3}, {0, 1, 3, 2}};
  const Vec4 n = cell_normal(mesh, 0);
  EXPECT_DOUBLE_EQ(length(n), 6.0 * (2.0 * 3.0 * 4.0 / 6.0));
  EXPECT_EQ(n, -cell_normal(mesh, 1));
  EXPECT_EQ(cell_normals(mesh)[0], (Vec4{0, 0, 0, -1}));
}

TEST(Intersect, AgreesWithBruteForceAndCorrectedCramerOnRandomCases) {
  Rng rng(11);
  int hits = 0, misses = 0;
  for (int i = 0; i < 20000; ++i) {
    const std::array<Vec4, 4> v{random_vec(rng), random_vec(rng), random_vec(rng), random_vec(rng)};
    const Vec4 o = 2.0 * random_vec(rng);
    // Half the rays aim at a point of the cell's hyperplane near the cell, so hits are common.
    Vec4 dir = random_vec(rng);
    if (i % 2 == 0) {
      const double l2 = rng.uniform() * 1.4 - 0.2, l3 = rng.uniform() * 1.4 - 0.2, l4 = rng.uniform() * 1.4 - 0.2;
      dir = v[0] + l2 * (v[1] - v[0]) + l3 * (v[2] - v[0]) + l4 * (v[3] - v[0]) - o;
    }
    const auto exact = brute_force(o, dir, v);
    if (!exact) continue;
    const auto [t, l2, l3, l4] = *exact;
    const long double margin = 1e-6;
    const bool clearly_in =
        t > margin && t < 10 - margin && l2 > margin && l3 > margin && l4 > margin && l2 + l3 + l4 < 1 - margin;
    const bool clearly_out =
        t < -margin || t > 10 + margin || l2 < -margin || l3 < -margin || l4 < -margin || l2 + l3 + l4 > 1 + margin;
    const auto hit = intersect(make_cell_plane(v[0], v[1], v[2], v[3]), o, dir, 0.0, 10.0);
    if (clearly_in) {
      ++hits;
      ASSERT_TRUE(hit) << "case " << i;
      EXPECT_NEAR(hit->t, static_cast<double>(t), 1e-9 * std::max(1.0L, std::fabs(t)));
      EXPECT_NEAR(hit->l2, static_cast<double>(l2), 1e-8);
      EXPECT_NEAR(hit->l3, static_cast<double>(l3), 1e-8);
      EXPECT_NEAR(hit->l4, static_cast<double>(l4), 1e-8);
    } else if (clearly_out) {
      ++misses;
      EXPECT_FALSE(hit) << "case " << i;
    }
    // The Cramer formulas written in intersect.hpp, checked on the same system.
    const Vec4 e1 = v[1] - v[0], e2 = v[2] - v[0], e3 = v[3] - v[0], q = o - v[0];
    const double den = det(dir, e1, e2, e3);
    if (std::abs(den) > 1e-6) {
      EXPECT_NEAR(-det(q, e1, e2, e3) / den, static_cast<double>(t), 1e-7 * std::max(1.0L, std::fabs(t)));
      EXPECT_NEAR(det(dir, q, e2, e3) / den, static_cast<double>(l2), 1e-7 * std::max(1.0L, std::fabs(l2)));
      EXPECT_NEAR(det(dir, e1, q, e3) / den, static_cast<double>(l3), 1e-7 * std::max(1.0L, std::fabs(l3)));
      EXPECT_NEAR(det(dir, e1, e2, q) / den, static_cast<double>(l4), 1e-7 * std::max(1.0L, std::fabs(l4)));
    }
  }
  EXPECT_GT(hits, 400);
  EXPECT_GT(misses, 1000);
}

// A cell in the hyperplane w = 0 and a ray through its interior point p at a grazing angle.
struct Grazing {
  std::array<Vec4, 4> v{Vec4{0, 0, 0, 0}, Vec4{1, 0, 0, 0}, Vec4{0, 1, 0, 0}, Vec4{0, 0, 1, 0}};
  Vec4 p{0.2, 0.3, 0.1, 0};
};

TEST(Intersect, NearParallelRaysHitWhereTheyShould) {
  const Grazing g;
  const CellPlane cell = make_cell_plane(g.v[0], g.v[1], g.v[2], g.v[3]);
  for (const double slope : {1e-3, 1e-6, 1e-9, 1e-11}) {
    const Vec4 dir = normalize(Vec4{1, 1, 1, slope});
    const double s = 0.05;  // distance from the origin to p, inside the cell whatever the slope
    const Vec4 o = g.p - s * dir;
    const auto hit = intersect(cell, o, dir, 0.0, 1.0);
    ASSERT_TRUE(hit) << "slope " << slope;
    // t's relative error grows like rounding / slope: the problem's own conditioning.
    EXPECT_NEAR(hit->t, s, 1e-15 / slope + 1e-15) << "slope " << slope;
    const Vec4 at = g.v[0] + hit->l2 * (g.v[1] - g.v[0]) + hit->l3 * (g.v[2] - g.v[0]) + hit->l4 * (g.v[3] - g.v[0]);
    EXPECT_NEAR(length(at - (o + hit->t * dir)), 0.0, 1e-12);  // barycentrics consistent with the hit point
  }
}

TEST(Intersect, ParallelRaysMissWithoutNaN) {
  const Grazing g;
  const CellPlane cell = make_cell_plane(g.v[0], g.v[1], g.v[2], g.v[3]);
  for (const double slope : {0.0, 1e-14, -1e-14}) {
    const Vec4 dir = normalize(Vec4{1, 1, 1, slope});
    EXPECT_FALSE(intersect(cell, g.p - 0.05 * dir, dir, 0.0, 1.0)) << "slope " << slope;
  }
  // A ray lying in the hyperplane itself.
  EXPECT_FALSE(intersect(cell, Vec4{-1, 0.1, 0.1, 0}, Vec4{1, 0, 0, 0}, 0.0, 10.0));
}

TEST(Intersect, ThinCellsAreHitAndFlatOnesAreSkipped) {
  Rng rng(5);
  const Vec4 a{0, 0, 0, 0}, b{1, 0, 0, 0}, c{0, 1, 0, 0};
  for (const double height : {1e-3, 1e-6, 1e-9}) {
    // D nearly in the plane of A, B, C: a sliver with 3-volume proportional to `height`.
    const Vec4 d = a + 0.3 * (b - a) + 0.3 * (c - a) + Vec4{0, 0, height, 0};
    const CellPlane cell = make_cell_plane(a, b, c, d);
    ASSERT_FALSE(cell.degenerate) << height;
    for (int i = 0; i < 200; ++i) {
      const double l2 = 0.1 + 0.2 * rng.uniform(), l3 = 0.1 + 0.2 * rng.uniform(), l4 = 0.1 + 0.2 * rng.uniform();
      const Vec4 p = a + l2 * (b - a) + l3 * (c - a) + l4 * (d - a);
      const Vec4 o = p + Vec4{rng.symmetric(), rng.symmetric(), rng.symmetric(), 1.0};
      const auto hit = intersect(cell, o, p - o, 0.0, 2.0);
      ASSERT_TRUE(hit) << height;
      EXPECT_NEAR(hit->t, 1.0, 1e-9);
      EXPECT_NEAR(hit->l2, l2, 1e-6);
      EXPECT_NEAR(hit->l3, l3, 1e-6);
      EXPECT_NEAR(hit->l4, l4, 1e-6);
    }
  }
  const Vec4 flat = a + 0.3 * (b - a) + 0.3 * (c - a) + Vec4{0, 0, 1e-15, 0};
  const CellPlane cell = make_cell_plane(a, b, c, flat);
  EXPECT_TRUE(cell.degenerate);
  EXPECT_FALSE(intersect(cell, Vec4{0.2, 0.2, 0, 1}, Vec4{0, 0, 0, -1}, 0.0, 2.0));
}

TEST(Intersect, RespectsTheOpenLowerAndClosedUpperBound) {
  const CellPlane cell = make_cell_plane({0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0});
  const Vec4 o{0.1, 0.1, 0.1, 1}, dir{0, 0, 0, -1};
  EXPECT_TRUE(intersect(cell, o, dir, 0.0, 1.0));
  EXPECT_FALSE(intersect(cell, o, dir, 0.0, 0.999));
  EXPECT_FALSE(intersect(cell, o, dir, 1.0, 2.0));
  EXPECT_FALSE(intersect(cell, o, -dir, 0.0, 2.0));  // behind the origin
}

}  // namespace
}  // namespace ao4d
