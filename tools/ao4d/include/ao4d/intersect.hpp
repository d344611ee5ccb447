// Ray-tetrahedron intersection in R^4.
//
// The system is O + t*Dir = A + l2*(B-A) + l3*(C-A) + l4*(D-A). With e1 = B-A, e2 = C-A, e3 = D-A,
// q = O-A and Den = det(Dir, e1, e2, e3), Cramer's rule gives (every determinant 4x4):
//   t  = -det(q, e1, e2, e3) / Den      l2 = det(Dir, q, e2, e3) / Den
//   l3 =  det(Dir, e1, q, e3) / Den     l4 = det(Dir, e1, e2, q) / Den
// The thesis's slides have a 3-column numerator for t with the wrong sign and Den itself as the
// numerator of l4 (so l4 == 1 always), which explains hits and misses that looked arbitrary.
//
// Solver chosen here: the same solution, decoupled and precomputed per cell. Den is
// dot(Dir, cross(e1, e2, e3)), so t is the distance to the cell's hyperplane along the ray,
// t = dot(n, A-O) / dot(n, Dir) with the unit normal n, and once the hit point P is known the
// barycentrics are l_k = dot(d_k, P-A) with the cell's dual basis d_k (d_k . e_j = delta_kj,
// d_k . n = 0). Why not per-ray Cramer: its five 4x4 determinants (about 200 flops) cancel
// catastrophically for near-parallel rays, and each l_k then carries its own rounding amplified by
// 1/Den, so two cells sharing an edge can both reject a ray (a crack in a closed surface).
// Here the ray enters only through t (an unavoidable ill-conditioning of the problem, the
// hit point slides along the ray), while the barycentrics are a well-conditioned function of
// the computed P, so the edge tests of neighbouring cells agree; a small barycentric tolerance
// closes the remaining rounding gaps. A ray test is five dot products. Rays within 1e-12 rad of
// the hyperplane and cells whose 3-volume is below 1e-12 of their edge-length product are
// treated as misses: such a cell has no area to hit, and its neighbours cover its surface.
// The Intersect tests in tests/ao4d/geometry_test.cpp check this against a pivoted Gaussian
// elimination, with near-parallel rays and near-degenerate cells.
#pragma once

#include "ao4d/vec4.hpp"

#include <optional>

namespace ao4d {

struct CellPlane {
    Vec4 a;                 // first vertex
    Vec4 normal;            // unit normal, cross(e1, e2, e3) normalised; zero when degenerate
    Vec4 dual[3];           // dual basis of (e1, e2, e3) inside the hyperplane
    bool degenerate = true;
};

CellPlane make_cell_plane(const Vec4& a, const Vec4& b, const Vec4& c, const Vec4& d);

struct TetHit {
    double t = 0;
    double l2 = 0, l3 = 0, l4 = 0;  // barycentrics of B, C, D; A's is 1 - l2 - l3 - l4
};

// Hit with t in (t_min, t_max]; `dir` need not be unit length (t is in units of |dir|).
std::optional<TetHit> intersect(const CellPlane& cell, const Vec4& origin, const Vec4& dir, double t_min, double t_max);

}  // namespace ao4d
