// Small 4D vector type in double precision. glm::dvec4 lacks the generalised cross product and
// 4x4 determinants with the sign conventions used here, so the few operations needed live in one
// place with their conventions written down.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

namespace ao4d {

struct Vec4 {
    double x = 0, y = 0, z = 0, w = 0;

    constexpr double operator[](std::size_t i) const { return i == 0 ? x : i == 1 ? y : i == 2 ? z : w; }
    constexpr double& operator[](std::size_t i) { return i == 0 ? x : i == 1 ? y : i == 2 ? z : w; }

    constexpr Vec4& operator+=(const Vec4& o) { x += o.x; y += o.y; z += o.z; w += o.w; return *this; }
    constexpr Vec4& operator-=(const Vec4& o) { x -= o.x; y -= o.y; z -= o.z; w -= o.w; return *this; }
    constexpr Vec4& operator*=(double s) { x *= s; y *= s; z *= s; w *= s; return *this; }
    friend constexpr bool operator==(const Vec4&, const Vec4&) = default;
};

constexpr Vec4 operator+(Vec4 a, const Vec4& b) { return a += b; }
constexpr Vec4 operator-(Vec4 a, const Vec4& b) { return a -= b; }
constexpr Vec4 operator-(const Vec4& a) { return {-a.x, -a.y, -a.z, -a.w}; }
constexpr Vec4 operator*(Vec4 a, double s) { return a *= s; }
constexpr Vec4 operator*(double s, Vec4 a) { return a *= s; }
constexpr Vec4 operator/(const Vec4& a, double s) { return {a.x / s, a.y / s, a.z / s, a.w / s}; }

constexpr double dot(const Vec4& a, const Vec4& b) { return a.x * b.x + a.y * b.y + a.z * b.z + a.w * b.w; }
inline double length(const Vec4& a) { return std::sqrt(dot(a, a)); }
// Returns the zero vector for a zero input so callers can test for degeneracy afterwards.
inline Vec4 normalize(const Vec4& a) {
    const double l = length(a);
    return l > 0 ? a / l : Vec4{};
}
constexpr Vec4 min(const Vec4& a, const Vec4& b) {
    return {a.x < b.x ? a.x : b.x, a.y < b.y ? a.y : b.y, a.z < b.z ? a.z : b.z, a.w < b.w ? a.w : b.w};
}
constexpr Vec4 max(const Vec4& a, const Vec4& b) {
    return {a.x > b.x ? a.x : b.x, a.y > b.y ? a.y : b.y, a.z > b.z ? a.z : b.z, a.w > b.w ? a.w : b.w};
}

// 3x3 determinant of the rows (a, b, c) restricted to the columns i < j < k.
constexpr double minor3(const Vec4& a, const Vec4& b, const Vec4& c, std::size_t i, std::size_t j, std::size_t k) {
    return a[i] * (b[j] * c[k] - b[k] * c[j]) - a[j] * (b[i] * c[k] - b[k] * c[i]) + a[k] * (b[i] * c[j] - b[j] * c[i]);
}

// Generalised cross product: the cofactor expansion of the formal determinant with rows
// (e_x e_y e_z e_w; a; b; c) along its first row, so that dot(cross(a, b, c), v) == det(v, a, b, c)
// for every v. The thesis's slides drop the alternating signs (-, on y and w), which makes the
// result not orthogonal to a, b, c in general.
constexpr Vec4 cross(const Vec4& a, const Vec4& b, const Vec4& c) {
    return {minor3(a, b, c, 1, 2, 3), -minor3(a, b, c, 0, 2, 3), minor3(a, b, c, 0, 1, 3), -minor3(a, b, c, 0, 1, 2)};
}

// Determinant of the 4x4 matrix with rows (or, equally, columns) a, b, c, d.
constexpr double det(const Vec4& a, const Vec4& b, const Vec4& c, const Vec4& d) { return dot(a, cross(b, c, d)); }

}  // namespace ao4d
