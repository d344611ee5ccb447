// Ambient occlusion against analytic values, and the BVH against brute force. A binomial AO
// estimate from K rays has standard deviation sqrt(p (1 - p) / K); tolerances are stated in it.
#include "ao4d/scene.hpp"
#include "ao4d/sampling.hpp"
#include "ao4d/shapes.hpp"
#include "helpers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

namespace ao4d {
namespace {

double binomial_sd(double p, int rays) { return std::sqrt(p * (1 - p) / rays); }

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
    const double ao = ambient_occlusion(scene, {delta, delta, delta, 0}, {0, 0, 0, 1}, params, point_seed(1, 0));
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
        const Vec4 dir = i % 2 ? uniform_sphere(rng) : normalize(0.5 * Vec4{rng.symmetric(), rng.symmetric(), rng.symmetric(), rng.symmetric()} - o);
        double best = std::numeric_limits<double>::infinity();
        for (const Cell& c : mesh.cells) {
            const auto hit = intersect(make_cell_plane(mesh.vertices[c[0]], mesh.vertices[c[1]], mesh.vertices[c[2]], mesh.vertices[c[3]]),
                                       o, dir, 0.0, 10.0);
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
    const Scene scene(test::floor_mesh(1.0));
    const auto hit = scene.closest_hit({0.1, 0.2, 0.3, 1}, {0, 0, 0, -1}, 0.0, 2.0);
    ASSERT_TRUE(hit);
    const auto again = scene.closest_hit({0.1, 0.2, 0.3, 1}, {0, 0, 0, -1}, 0.0, 2.0, hit->cell);
    if (again) {
        EXPECT_NE(again->cell, hit->cell);  // a neighbour sharing the hit edge may still answer
    }
}

}  // namespace
}  // namespace ao4d
