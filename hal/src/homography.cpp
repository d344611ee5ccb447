#include "homography.h"

#include <cmath>
#include <vector>

namespace hal::detail {

namespace {

// Translation + isotropic scale moving the points' centroid to 0 and mean distance to sqrt(2)
// (Hartley), which keeps the 8x8 normal equations well conditioned for pixel coordinates.
Mat3 normaliser(std::span<const Point> p) {
  double cx = 0, cy = 0;
  for (const auto& q : p) cx += q.x, cy += q.y;
  cx /= static_cast<double>(p.size());
  cy /= static_cast<double>(p.size());
  double d = 0;
  for (const auto& q : p) d += std::hypot(q.x - cx, q.y - cy);
  d /= static_cast<double>(p.size());
  const double s = d > 0 ? std::sqrt(2.0) / d : 1.0;
  return {s, 0, -s * cx, 0, s, -s * cy, 0, 0, 1};
}

Mat3 mul(const Mat3& a, const Mat3& b) {
  Mat3 r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) r[i * 3 + j] += a[i * 3 + k] * b[k * 3 + j];
  return r;
}

}  // namespace

Point apply(const Mat3& h, double x, double y) {
  const double w = h[6] * x + h[7] * y + h[8];
  return {(h[0] * x + h[1] * y + h[2]) / w, (h[3] * x + h[4] * y + h[5]) / w};
}

bool invert(const Mat3& m, Mat3& out) {
  const double a = m[0], b = m[1], c = m[2], d = m[3], e = m[4], f = m[5], g = m[6], h = m[7], i = m[8];
  const double A = e * i - f * h, B = -(d * i - f * g), C = d * h - e * g;
  const double det = a * A + b * B + c * C;
  if (std::abs(det) < 1e-12) return false;
  out = {A / det, -(b * i - c * h) / det, (b * f - c * e) / det, B / det, (a * i - c * g) / det, -(a * f - c * d) / det,
         C / det, -(a * h - b * g) / det, (a * e - b * d) / det};
  return true;
}

bool fit_homography(std::span<const Point> src, std::span<const Point> dst, Mat3& h) {
  if (src.size() < 4 || src.size() != dst.size()) return false;
  const Mat3 ts = normaliser(src), td = normaliser(dst);
  // Normal equations of the 2n x 8 DLT system, accumulated directly.
  double ata[8][9] = {};
  for (std::size_t n = 0; n < src.size(); ++n) {
    const Point s = apply(ts, src[n].x, src[n].y), d = apply(td, dst[n].x, dst[n].y);
    const double rows[2][9] = {{s.x, s.y, 1, 0, 0, 0, -d.x * s.x, -d.x * s.y, d.x},
                               {0, 0, 0, s.x, s.y, 1, -d.y * s.x, -d.y * s.y, d.y}};
    for (const auto& r : rows)
      for (int i = 0; i < 8; ++i)
        for (int j = 0; j < 9; ++j) ata[i][j] += r[i] * r[j];
  }
  // Gauss-Jordan with partial pivoting on the augmented 8x9 system.
  for (int col = 0; col < 8; ++col) {
    int pivot = col;
    for (int r = col + 1; r < 8; ++r)
      if (std::abs(ata[r][col]) > std::abs(ata[pivot][col])) pivot = r;
    if (std::abs(ata[pivot][col]) < 1e-12) return false;
    for (int j = 0; j < 9; ++j) std::swap(ata[col][j], ata[pivot][j]);
    for (int r = 0; r < 8; ++r) {
      if (r == col) continue;
      const double f = ata[r][col] / ata[col][col];
      for (int j = col; j < 9; ++j) ata[r][j] -= f * ata[col][j];
    }
  }
  Mat3 hn;
  for (int i = 0; i < 8; ++i) hn[i] = ata[i][8] / ata[i][i];
  hn[8] = 1;
  Mat3 td_inv;
  if (!invert(td, td_inv)) return false;
  h = mul(td_inv, mul(hn, ts));
  for (double& v : h) v /= h[8];
  return std::isfinite(h[0]);
}

}  // namespace hal::detail
