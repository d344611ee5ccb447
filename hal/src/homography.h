#pragma once
#include <array>
#include <span>

namespace hal::detail {

using Mat3 = std::array<double, 9>;
struct Point {
  double x, y;
};

// Least-squares homography mapping src[i] to dst[i] (at least 4 points, no 3 collinear), by the
// normalised DLT with h33 = 1. False when the system is degenerate.
bool fit_homography(std::span<const Point> src, std::span<const Point> dst, Mat3& h);
Point apply(const Mat3& h, double x, double y);
bool invert(const Mat3& m, Mat3& out);

}  // namespace hal::detail
