// Ambient occlusion against analytic values, and the BVH against brute force. A binomial AO
// estimate from K rays has standard deviation sqrt(p (1 - p) / K); tolerances are stated in it.
#include "ao4d/sampling.hpp"
#include "ao4d/scene.hpp"
#include "ao4d/shapes.hpp"
#include "helpers.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

namespace ao4d {
namespace {

double binomial_sd(double p, int rays) {
  return std::sqrt(p * (1 - p) / rays);
}

TEST(Ao, IsZeroOnALoneHyperplane) {
  const Scene scene(test::floor_mesh(2.0));
  AoParams params;
  params.radius = 10.0;  // far longer than the plane is wide: still nothing above it to hit
  params.rays = 512;
  Rng rng(4);
  for (const bool cosine : {false, true}) {
    params.cosine = cosine;
    for (std::uint64_t i = 0; i < 20; ++i) {
      const Vec4 p{1.9 * rng.symmetric(), 1.9 * rng.symmetric(), 1.9 * rng.symmetric(), 0};
      EXPECT_EQ(ambient_occlusion(scene, p, {0, 0, 0, 1}, params, i), 0.0);
    }
  }
}

TEST(Ao, IsOneInsideAClosedHypersphere) {
  const Scene scene(make_shape("hypersphere", 6));
  AoParams params;
  params.radius = 3.0;
  params.rays = 2000;
  Rng rng(5);
  for (const bool cosine : {false, true}) {
    params.cosine = cosine;
    for (std::uint64_t i = 0; i < 10; ++i) {
      // Any point well inside and any normal: every ray must leave through the closed surface.
      const Vec4 p = 0.5 * Vec4{rng.symmetric(), rng.symmetric(), rng.symmetric(), rng.symmetric()};
      const Vec4 n = uniform_sphere(rng);
      EXPECT_EQ(ambient_occlusion(scene, p, n, params, i), 1.0) << "point " << i;
    }
  }
}

// A point on the floor at the foot of k perpendicular walls sees 2^-k of its hemisphere open, for
// uniform and cosine weights alike (each reflection x_i -> -x_i keeps both weights).
class Corner : public testing::TestWithParam<std::tuple<int, bool>> {};

TEST_P(Corner, GivesOneMinusTwoToTheMinusK) {
  const auto [k, cosine] = GetParam();
  const Scene scene(test::corner_mesh(k, 4.0));
  AoParams params;
  params.radius = 1.0;
  params.rays = 20000;
  params.cosine = cosine;
  // The point sits delta off each wall; rays nearly parallel to a wall (|d_i| < delta / radius)
  // then miss it, a bias below 2 * delta * (2 / pi) per wall, far inside the tolerance.
  const double delta = 1e-4;
  const double expected = 1.0 - std::ldexp(1.0, -k);
  const double ao =
      ambient_occlusion(scene, {delta, delta, delta, 0}, {0, 0, 0, 1}, params, point_seed(1, SeedStream::points, 0));
  EXPECT_NEAR(ao, expected, 4.0 * binomial_sd(expected, params.rays) + 3 * 2 * delta);
}

INSTANTIATE_TEST_SUITE_P(Walls, Corner, testing::Combine(testing::Values(1, 2, 3), testing::Bool()));

// Above a plane at height h with the normal facing it, a ray of length R hits when cos >= h / R:
// P = (Int_a^1 sqrt(1 - x^2) dx) / (pi / 4) for uniform directions, (1 - a^2)^(3/2) for cosine ones.
TEST(Ao, FacingAPlaneMatchesTheRadiusDistribution) {
  const Scene scene(test::floor_mesh(50.0));
  AoParams params;
  params.radius = 1.0;
  params.rays = 20000;
  const double a = 0.5;
  const double uniform = (std::numbers::pi / 4 - (a * std::sqrt(1 - a * a) + std::asin(a)) / 2) / (std::numbers::pi / 4);
  const double cosine = std::pow(1 - a * a, 1.5);
  params.cosine = false;
  EXPECT_NEAR(ambient_occlusion(scene, {0, 0, 0, a}, {0, 0, 0, -1}, params, 3), uniform, 4 * binomial_sd(uniform, params.rays));
  params.cosine = true;
  EXPECT_NEAR(ambient_occlusion(scene, {0, 0, 0, a}, {0, 0, 0, -1}, params, 3), cosine, 4 * binomial_sd(cosine, params.rays));
}

TEST(Ao, MirrorImagesInTheTwoTetrahedraSceneGetTheSameOcclusion) {
  // The thesis saw its left object treated differently from the right one.
  const Scene scene(make_shape("two-tetrahedra", 0));
  AoParams params;
  params.radius = 1.0;
  params.rays = 20000;
  const Vec4 up{0, 0, 0, -1};
  for (const Vec4& left : {Vec4{-0.2, 0.0, 0.1, 0}, Vec4{-1.0, 0.8, 0.0, 0}, Vec4{-1.6, -0.3, 0.2, 0}}) {
    const Vec4 right{-left.x, left.y, left.z, left.w};
    const double l = ambient_occlusion(scene, left, up, params, 1);
    const double r = ambient_occlusion(scene, right, up, params, 2);
    EXPECT_GT(l, 0.0);
    // Independent estimates: their difference has sd sqrt(2) * binomial sd.
    EXPECT_NEAR(l, r, 4 * std::sqrt(2.0) * binomial_sd(std::max(l, 0.01), params.rays)) << left.x;
  }
}

// The first hit of a camera ray along +w (as render_volume casts it) and the normal facing the camera.
struct SurfacePoint {
  Vec4 position, normal;
  std::uint32_t cell = kNoCell;
};

SurfacePoint seen_from_the_camera(const Scene& scene, double x, double y, double z) {
  const Vec4 origin{x, y, z, -2}, dir{0, 0, 0, 1};
  const auto hit = scene.closest_hit(origin, dir, 0.0, 10.0);
  if (!hit) return {};
  Vec4 n = scene.normal(hit->cell);
  if (dot(n, dir) > 0) n = -n;
  return {origin + hit->t * dir, n, hit->cell};
}

// The indent is a bowl cut 0.3 deep into the -w face by a ball of radius 0.6 centred 0.3 beyond it
// (shapes.cpp). From the bottom of the bowl the rim is 60 degrees off the normal, and every ray
// further out hits the bowl within 2 * 0.6 * cos(60 deg) = 0.6 < radius: for the exact bowl the AO
// is the share of the 4D hemisphere beyond 60 degrees, (pi/4 - pi/6 + sin(120 deg)/4) / (pi/4) =
// 0.609 (density sin^2). The marched bowl at grid 10 is shallower and faceted (0.55); the bounds
// below hold that with room for 4 sd of sampling (0.045 at 2000 rays). The flat part of the face is
// the object's extreme in -w (every vertex has w >= -0.8), so nothing lies in its hemisphere.
TEST(Ao, TheIndentsFloorIsOccludedAndTheFlatFaceIsNot) {
  const Scene indented(make_shape("indented-tesseract", 10)), plain(make_shape("tesseract", 10));
  AoParams params;
  params.radius = 0.25 * indented.diagonal();
  params.rays = 2000;
  ASSERT_GT(params.radius, 0.6);

  const SurfacePoint floor = seen_from_the_camera(indented, 0, 0, 0);
  ASSERT_NE(floor.cell, kNoCell);
  EXPECT_NEAR(floor.position.w, -0.5, 0.02);  // the bowl's bottom, not the face at -0.8
  const double in_bowl = ambient_occlusion(indented, floor.position, floor.normal, params, 1, floor.cell);
  EXPECT_GT(in_bowl, 0.45);
  EXPECT_LT(in_bowl, 0.7);

  // The same camera ray on the plain tesseract meets the flat face: nothing occludes it.
  const SurfacePoint face = seen_from_the_camera(plain, 0, 0, 0);
  ASSERT_NE(face.cell, kNoCell);
  EXPECT_NEAR(face.position.w, -0.8, 1e-12);
  EXPECT_EQ(ambient_occlusion(plain, face.position, face.normal, params, 1, face.cell), 0.0);

  // Away from the indent (more than its rim radius 0.52 plus a grid step from the axis, and a grid
  // step inside the face's edges), the indented tesseract's face is flat and unoccluded too.
  for (const Vec4& at : {Vec4{0.55, -0.5, 0.45, 0}, Vec4{-0.5, 0.5, -0.5, 0}, Vec4{0.5, 0.55, -0.5, 0}}) {
    const SurfacePoint flat = seen_from_the_camera(indented, at.x, at.y, at.z);
    ASSERT_NE(flat.cell, kNoCell);
    EXPECT_NEAR(flat.position.w, -0.8, 1e-12) << at.x;
    EXPECT_EQ(ambient_occlusion(indented, flat.position, flat.normal, params, 2, flat.cell), 0.0) << at.x;
  }
}

// A side cell of a pyramid in the two-tetrahedra scene and a point on it at height h above the floor.
struct PyramidPoint {
  Vec4 position, normal;
  std::uint32_t cell = kNoCell;
};

std::vector<PyramidPoint> pyramid_points(const Scene& scene, double h) {
  std::vector<PyramidPoint> points;
  const TetMesh& mesh = scene.mesh();
  for (std::uint32_t i = 0; i < mesh.cells.size(); ++i) {
    Vec4 apex, base;
    int n_apex = 0;
    for (std::uint32_t v : mesh.cells[i])
      if (mesh.vertices[v].w < -0.5) {
        apex = mesh.vertices[v];
        ++n_apex;
      } else {
        base += mesh.vertices[v] / 3.0;
      }
    if (n_apex == 1) points.push_back({h * apex + (1 - h) * base, scene.normal(i), i});  // apex at w = -1
  }
  return points;
}

// P(d_w >= c) for d uniform, or cosine-weighted, on the hemisphere around the unit normal n. The
// projection of the uniform distribution on S^3 onto a 2-plane is uniform on the unit disk, so in
// the plane of e_w and n (coordinates a along e_w, b along n's other part) this is an area ratio,
// integrated here over a in fine strips; the cosine weight is the linear function n . (a, b).
double floor_hit_share(const Vec4& n, double c, bool cosine) {
  const double nw = n.w, nt = std::sqrt(1 - nw * nw);
  constexpr int kStrips = 100000;
  double hit = 0, all = 0;
  for (int i = 0; i < kStrips; ++i) {
    const double a = -1 + (i + 0.5) * 2.0 / kStrips, half = std::sqrt(1 - a * a);
    const double b0 = std::clamp(-nw * a / nt, -half, half);  // the hemisphere is b > b0
    const double strip = cosine ? nw * a * (half - b0) + nt * (half * half - b0 * b0) / 2 : half - b0;
    all += strip;
    if (a >= c) hit += strip;
  }
  return hit / all;
}

// The thesis's scene gave tetrahedra AO of exactly 0 or 1. Here a point at height h on a pyramid's
// side, with rays of length R = 0.5, is occluded exactly by the rays that reach the floor, d_w >=
// h / R: the pyramid is convex (its own cells face away), the other pyramid is more than R away
// (the bases span x in [-1.5, -0.5] and [0.5, 1.5]), and the floor spans [-2, 2]^3, so it lies
// under every point within R of the side (|x| < 1.5, |y|, |z| < 0.5). That share lies strictly between 0 and 1, and is the same
// for all eight side cells.
TEST(Ao, PyramidSidesAreOccludedByTheFloorAsTheGeometrySays) {
  const Scene scene(make_shape("two-tetrahedra", 0));
  AoParams params;
  params.radius = 0.5;
  params.rays = 20000;
  const double h = 0.25;
  const auto points = pyramid_points(scene, h);
  ASSERT_EQ(points.size(), 8u);
  std::uint64_t seed = 100;
  for (const bool cosine : {false, true}) {
    params.cosine = cosine;
    for (const PyramidPoint& p : points) {
      const double expected = floor_hit_share(p.normal, h / params.radius, cosine);
      EXPECT_GT(expected, 0.05);
      EXPECT_LT(expected, 0.95);
      const double ao = ambient_occlusion(scene, p.position, p.normal, params, ++seed, p.cell);
      EXPECT_NEAR(ao, expected, 4 * binomial_sd(expected, params.rays)) << "cell " << p.cell << (cosine ? " cosine" : "");
    }
  }
}

// The per-vertex AO of the mesh output. Each pyramid's base vertices rest on the floor: with rays of
// length R = 0.5 (the other pyramid is farther) exactly the rays into the floor, d_w > 0, are
// occluded; the apexes look at open sky and the floor's corners are more than R from anything.
TEST(Ao, VerticesRestingOnTheFloorAreOccludedByIt) {
  const Scene scene(make_shape("two-tetrahedra", 0));
  const TetMesh& mesh = scene.mesh();
  const auto normals = vertex_normals(mesh);
  AoParams params;
  params.radius = 0.5;
  params.rays = 20000;
  for (const bool cosine : {false, true}) {
    params.cosine = cosine;
    const auto ao = vertex_ambient_occlusion(scene, params);
    ASSERT_EQ(ao.size(), 18u);
    int base = 0;
    for (std::size_t v = 0; v < ao.size(); ++v) {
      const Vec4& p = mesh.vertices[v];
      const bool floor_corner = std::abs(p.x) == 2, apex = p.w == -1;
      if (floor_corner || apex) {
        EXPECT_EQ(ao[v], 0.0) << "vertex " << v;
        continue;
      }
      ++base;
      const double expected = floor_hit_share(normals[v], 0.0, cosine);  // 0.27 uniform
      EXPECT_GT(expected, 0.1);
      EXPECT_NEAR(ao[v], expected, 4 * binomial_sd(expected, params.rays)) << "vertex " << v << (cosine ? " cosine" : "");
    }
    EXPECT_EQ(base, 8);
  }
}

// With the command's default radius (a quarter of the diagonal, 1.75) the pyramids see each other
// and the floor's edge, so there is no closed form; but mirror points must get the same AO, and
// every point of a pyramid's side below the radius has floor below it (AO > 0) and open sky above
// it (AO < 1).
TEST(Ao, MirrorPointsOnTheTwoPyramidsGetTheSameOcclusion) {
  const Scene scene(make_shape("two-tetrahedra", 0));
  AoParams params;
  params.radius = 0.25 * scene.diagonal();
  params.rays = 20000;
  std::uint64_t seed = 200;
  for (const double h : {0.1, 0.4, 0.7}) {
    const auto points = pyramid_points(scene, h);
    ASSERT_EQ(points.size(), 8u);
    for (const PyramidPoint& left : points) {
      if (left.position.x > 0) continue;
      const Vec4 mirror_position{-left.position.x, left.position.y, left.position.z, left.position.w};
      const Vec4 mirror_normal{-left.normal.x, left.normal.y, left.normal.z, left.normal.w};
      const auto right = std::find_if(points.begin(), points.end(), [&](const PyramidPoint& p) {
        return length(p.position - mirror_position) < 1e-12 && length(p.normal - mirror_normal) < 1e-12;
      });
      ASSERT_NE(right, points.end()) << "no mirror image of cell " << left.cell;
      const double l = ambient_occlusion(scene, left.position, left.normal, params, ++seed, left.cell);
      const double r = ambient_occlusion(scene, right->position, right->normal, params, ++seed, right->cell);
      for (const double ao : {l, r}) {
        EXPECT_GT(ao, 0.0) << "h " << h << ", cell " << left.cell;
        EXPECT_LT(ao, 1.0) << "h " << h << ", cell " << left.cell;
      }
      // Independent estimates: their difference has sd sqrt(2) times the binomial sd.
      EXPECT_NEAR(l, r, 4 * std::sqrt(2.0) * binomial_sd(0.5 * (l + r), params.rays)) << "h " << h << ", cell " << left.cell;
    }
  }
}

TEST(Ao, DoesNotDependOnTheThreadCount) {
  const Scene scene(make_shape("torus", 6));
  AoParams params;
  params.radius = 0.5;
  params.rays = 16;
  params.threads = 1;
  const auto one = vertex_ambient_occlusion(scene, params);
  params.threads = 3;
  EXPECT_EQ(vertex_ambient_occlusion(scene, params), one);
  params.seed = 2;
  EXPECT_NE(vertex_ambient_occlusion(scene, params), one);
}

TEST(Bvh, ClosestHitMatchesBruteForce) {
  const TetMesh mesh = make_shape("indented-tesseract", 5);
  const Scene scene(mesh);
  Rng rng(6);
  int hits = 0;
  for (int i = 0; i < 300; ++i) {
    const Vec4 o = 1.5 * Vec4{rng.symmetric(), rng.symmetric(), rng.symmetric(), rng.symmetric()};
    // Every other ray aims into the object, so hits and misses are both common.
    const Vec4 dir = i % 2 ? uniform_sphere(rng)
                           : normalize(0.5 * Vec4{rng.symmetric(), rng.symmetric(), rng.symmetric(), rng.symmetric()} - o);
    double best = std::numeric_limits<double>::infinity();
    for (const Cell& c : mesh.cells) {
      const auto hit = intersect(
          make_cell_plane(mesh.vertices[c[0]], mesh.vertices[c[1]], mesh.vertices[c[2]], mesh.vertices[c[3]]), o, dir, 0.0, 10.0);
      if (hit) best = std::min(best, hit->t);
    }
    const auto found = scene.closest_hit(o, dir, 0.0, 10.0);
    ASSERT_EQ(found.has_value(), std::isfinite(best)) << "ray " << i;
    if (found) {
      ++hits;
      EXPECT_DOUBLE_EQ(found->t, best);
      EXPECT_EQ(scene.occluded(o, dir, 0.0, best), true);
      EXPECT_EQ(scene.occluded(o, dir, 0.0, best * (1 - 1e-9)), false);
    }
  }
  EXPECT_GT(hits, 150);
}

TEST(Bvh, SkipsTheCellARayStartsOn) {
  // Two floors, w = 0 over w = -3. The ray meets the upper one at (0.1, 0.2, 0.3): in the box's
  // (u, v, w) = (0.55, 0.6, 0.65), all different, so inside one Kuhn cell and on no shared face.
  // The floors lie further apart than the cells' width, so the BVH splits them first and the ray
  // reaches the skipped cell before any cell below: a skip that ended the search would show.
  TetMesh mesh = test::floor_mesh(1.0);
  test::add_box(mesh, {-1, -1, -1, -3}, {2, 0, 0, 0}, {0, 2, 0, 0}, {0, 0, 2, 0}, {0, 0, 0, 1});
  const Scene scene(mesh);
  const Vec4 origin{0.1, 0.2, 0.3, 1}, down{0, 0, 0, -1};
  const auto hit = scene.closest_hit(origin, down, 0.0, 5.0);
  ASSERT_TRUE(hit);
  EXPECT_DOUBLE_EQ(hit->t, 1.0);
  ASSERT_LT(hit->cell, 6u) << "the upper floor's cells come first";
  // Skipping that cell, and only it: the ray passes through the upper floor and meets the lower one.
  const auto again = scene.closest_hit(origin, down, 0.0, 5.0, hit->cell);
  ASSERT_TRUE(again) << "skipping one cell hid the floor below it";
  EXPECT_DOUBLE_EQ(again->t, 4.0);
  EXPECT_GE(again->cell, 6u);
  EXPECT_TRUE(scene.occluded(origin, down, 0.0, 5.0, hit->cell));
  EXPECT_FALSE(scene.occluded(origin, down, 0.0, 3.5, hit->cell)) << "the skipped cell still occludes";
  // A ray starting on the cell, as AO rays do, sees only the floor below.
  const Vec4 on{0.1, 0.2, 0.3, 0};
  const auto below = scene.closest_hit(on, down, 0.0, 5.0, hit->cell);
  ASSERT_TRUE(below);
  EXPECT_DOUBLE_EQ(below->t, 3.0);
  EXPECT_GE(below->cell, 6u);
}

}  // namespace
}  // namespace ao4d
