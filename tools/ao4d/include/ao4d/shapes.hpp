// 4D test data: isosurfaces of implicit functions by marching simplices, and named shapes.
#pragma once

#include "ao4d/mesh.hpp"

#include <functional>
#include <string>
#include <vector>

namespace ao4d {

// Negative inside the object, positive outside.
using Field = std::function<double(const Vec4&)>;

// The surface {f = 0} of f sampled on a grid of `cells`^4 hypercubes over the box [lo, hi]. Each
// hypercube is split into the 24 Kuhn/Freudenthal pentatopes (one per permutation of the axes,
// walking from corner 0 to the opposite corner), which triangulate the grid conformingly. In each
// pentatope the linear interpolant's zero set is a tetrahedron (1 or 4 vertices inside) or a
// triangular prism (2 or 3 inside), the prism split into 3 tetrahedra with every quad face cut
// through its lowest-numbered vertex (Dompierre et al. 1999) so that neighbours agree. Vertices on
// grid edges are shared, cells are oriented outwards (away from the inside grid points, decided
// exactly from the grid's combinatorics), and f must be positive on the box's boundary for the
// result to be closed. A grid value < 0 is inside, >= 0 outside.
TetMesh march(const Field& f, const Vec4& lo, const Vec4& hi, int cells);

// Names accepted by make_shape, for --help and error messages.
const std::vector<std::string>& shape_names();
std::string shape_list();  // "a, b, c"

// A named shape with `grid` marching cells per axis (the two-tetrahedra scene ignores it).
// Throws std::invalid_argument naming the valid shapes for an unknown name.
TetMesh make_shape(const std::string& name, int grid);

}  // namespace ao4d
