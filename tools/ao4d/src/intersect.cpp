#include "ao4d/intersect.hpp"

#include <cmath>

namespace ao4d {

namespace {
// Relative thresholds; see the header for why each exists.
constexpr double kDegenerateVolume = 1e-12;
constexpr double kParallel = 1e-12;
// Barycentric slack that keeps closed meshes watertight along shared edges; a double hit on an edge
// is harmless for AO (any hit occludes) and for first-hit queries (the same t).
constexpr double kBaryTolerance = 1e-9;
}  // namespace

CellPlane make_cell_plane(const Vec4& a, const Vec4& b, const Vec4& c, const Vec4& d) {
  CellPlane cell;
  cell.a = a;
  const Vec4 e1 = b - a, e2 = c - a, e3 = d - a;
  const Vec4 n = cross(e1, e2, e3);
  const double scale = length(e1) * length(e2) * length(e3);
  if (!(length(n) > kDegenerateVolume * scale)) return cell;
  cell.normal = normalize(n);
  cell.degenerate = false;
  // d1 is orthogonal to e2, e3 and n, scaled so that d1 . e1 == 1; likewise d2 and d3.
  const Vec4 n1 = cell.normal;
  const Vec4 d1 = cross(e2, e3, n1), d2 = cross(e3, e1, n1), d3 = cross(e1, e2, n1);
  cell.dual[0] = d1 / dot(d1, e1);
  cell.dual[1] = d2 / dot(d2, e2);
  cell.dual[2] = d3 / dot(d3, e3);
  return cell;
}

std::optional<TetHit> intersect(const CellPlane& cell, const Vec4& origin, const Vec4& dir, double t_min, double t_max) {
  if (cell.degenerate) return std::nullopt;
  const double den = dot(cell.normal, dir);
  if (!(std::abs(den) > kParallel * length(dir))) return std::nullopt;
  const double t = dot(cell.normal, cell.a - origin) / den;
  if (!(t > t_min && t <= t_max)) return std::nullopt;
  const Vec4 q = origin + t * dir - cell.a;
  const TetHit hit{t, dot(cell.dual[0], q), dot(cell.dual[1], q), dot(cell.dual[2], q)};
  if (hit.l2 < -kBaryTolerance || hit.l3 < -kBaryTolerance || hit.l4 < -kBaryTolerance ||
      hit.l2 + hit.l3 + hit.l4 > 1 + kBaryTolerance)
    return std::nullopt;
  return hit;
}

}  // namespace ao4d
