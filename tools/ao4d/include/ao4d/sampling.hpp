// Random directions on the 3-sphere S^3 in R^4.
//
// The generator and every transform are written out here rather than taken from <random>'s
// distributions, whose algorithms are implementation-defined: the same seed must give the same AO
// with any standard library and any thread count.
#pragma once

#include "ao4d/vec4.hpp"

#include <cstdint>

namespace ao4d {

// xoshiro256** seeded through splitmix64.
class Rng {
public:
    explicit Rng(std::uint64_t seed);
    std::uint64_t next();
    double uniform();  // in [0, 1)
    double symmetric() { return 2.0 * uniform() - 1.0; }  // in [-1, 1)

private:
    std::uint64_t s_[4];
};

// The kinds of sample point, each with its own random stream: voxel i and vertex i of one run
// must not reuse each other's directions.
enum class SeedStream : std::uint64_t { points = 1, voxels = 2, vertices = 3 };

// The seed of one sample point (a line of a points file, a voxel, a vertex): results depend on the
// run's seed, the kind of point and its index only, never on which thread got the point. The three
// are chained through splitmix64's bijective mixer, so within a stream distinct indices give
// distinct seeds, and seeds of different streams or run seeds are unrelated.
std::uint64_t point_seed(std::uint64_t run_seed, SeedStream stream, std::uint64_t point_index);

// Uniform on S^3 by Marsaglia's (1972) method: two points uniform in the unit disk. Uniform
// generalised spherical angles, as in the thesis, crowd the poles and are not uniform.
Vec4 uniform_sphere(Rng& rng);

// Uniform on the hemisphere around the unit normal n: a uniform direction flipped to n's side.
Vec4 uniform_hemisphere(Rng& rng, const Vec4& n);

// Density cos(theta) / (4*pi/3) on the hemisphere around n: the integral of cos over the 4D
// hemisphere is 4*pi*Int_0^{pi/2} cos(t) sin^2(t) dt = 4*pi/3 (not pi as in 3D). Sampled by
// Malley's method, which holds in any dimension: a point uniform in the unit 3-ball of the
// tangent hyperplane, lifted onto the hemisphere.
Vec4 cosine_hemisphere(Rng& rng, const Vec4& n);

}  // namespace ao4d
