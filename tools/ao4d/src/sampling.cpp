#include "ao4d/sampling.hpp"

#include <cmath>

namespace ao4d {

namespace {

std::uint64_t splitmix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

constexpr std::uint64_t rotl(std::uint64_t x, int k) {
  return (x << k) | (x >> (64 - k));
}

}  // namespace

Rng::Rng(std::uint64_t seed) {
  for (std::uint64_t& s : s_) s = splitmix64(seed);
}

std::uint64_t Rng::next() {
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

double Rng::uniform() {
  return static_cast<double>(next() >> 11) * 0x1.0p-53;
}

std::uint64_t point_seed(std::uint64_t run_seed, SeedStream stream, std::uint64_t point_index) {
  // Each step is x -> mix(x), a bijection: a hash chain over (run seed, stream, index).
  const auto mix = [](std::uint64_t x) { return splitmix64(x); };
  return mix(mix(mix(run_seed) ^ static_cast<std::uint64_t>(stream)) ^ point_index);
}

Vec4 uniform_sphere(Rng& rng) {
  double x1, x2, s1, x3, x4, s2;
  do {
    x1 = rng.symmetric();
    x2 = rng.symmetric();
    s1 = x1 * x1 + x2 * x2;
  } while (s1 >= 1.0);
  do {
    x3 = rng.symmetric();
    x4 = rng.symmetric();
    s2 = x3 * x3 + x4 * x4;
  } while (s2 >= 1.0 || s2 == 0.0);
  const double f = std::sqrt((1.0 - s1) / s2);
  return {x1, x2, x3 * f, x4 * f};
}

Vec4 uniform_hemisphere(Rng& rng, const Vec4& n) {
  const Vec4 d = uniform_sphere(rng);
  return dot(d, n) < 0 ? -d : d;
}

Vec4 cosine_hemisphere(Rng& rng, const Vec4& n) {
  double u1, u2, u3, r2;
  do {
    u1 = rng.symmetric();
    u2 = rng.symmetric();
    u3 = rng.symmetric();
    r2 = u1 * u1 + u2 * u2 + u3 * u3;
  } while (r2 >= 1.0);
  double c = std::sqrt(1.0 - r2);
  // Householder reflection H = I - 2 v v^T / v.v maps e_x to +-n and (e_y, e_z, e_w) onto an
  // orthonormal basis of n's tangent hyperplane; the sign choice keeps v.v >= 2 (no cancellation).
  Vec4 v = n;
  if (n.x > 0) {
    v.x += 1.0;  // H e_x = -n
    c = -c;
  } else {
    v.x -= 1.0;  // H e_x = n
  }
  const Vec4 local{c, u1, u2, u3};
  return local - (2.0 * dot(v, local) / dot(v, v)) * v;
}

}  // namespace ao4d
