#include "ao4d/shapes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <unordered_map>
#include <utility>

namespace ao4d {

namespace {

// Interpolated vertices stay this fraction of an edge away from its ends: zeros of f at grid
// points would otherwise give several vertices at one position and cells of zero volume, whose
// normals (and so orientations) are undefined. The surface moves by at most 1e-3 of a cell.
constexpr double kEdgeClamp = 1e-3;

using Perm = std::array<int, 4>;

std::array<Perm, 24> kuhn_permutations() {
  std::array<Perm, 24> perms{};
  Perm p{0, 1, 2, 3};
  std::size_t i = 0;
  do perms[i++] = p;
  while (std::next_permutation(p.begin(), p.end()));
  return perms;
}

class Marcher {
 public:
  Marcher(const Field& f, const Vec4& lo, const Vec4& hi, int cells) : lo_(lo), cells_(cells), n_(cells + 1) {
    for (std::size_t a = 0; a < 4; ++a) {
      h_[a] = (hi[a] - lo[a]) / cells;
      if (h_[a] < 0) axis_sign_ = -axis_sign_;
    }
    stride_ = {1, n_, n_ * n_, n_ * n_ * n_};
    values_.resize(static_cast<std::size_t>(n_) * n_ * n_ * n_);
    for (std::int64_t l = 0; l < n_; ++l)
      for (std::int64_t k = 0; k < n_; ++k)
        for (std::int64_t j = 0; j < n_; ++j)
          for (std::int64_t i = 0; i < n_; ++i)
            values_[static_cast<std::size_t>(index(i, j, k, l))] = f(point(index(i, j, k, l)));
  }

  TetMesh run() {
    const auto perms = kuhn_permutations();
    for (std::int64_t l = 0; l < cells_; ++l)
      for (std::int64_t k = 0; k < cells_; ++k)
        for (std::int64_t j = 0; j < cells_; ++j)
          for (std::int64_t i = 0; i < cells_; ++i) {
            const std::int64_t base = index(i, j, k, l);
            int inside = 0;
            for (int corner = 0; corner < 16; ++corner) inside += value(base + offset(corner)) < 0;
            if (inside == 0 || inside == 16) continue;
            for (const Perm& p : perms) pentatope(base, p);
          }
    return std::move(mesh_);
  }

 private:
  std::int64_t index(std::int64_t i, std::int64_t j, std::int64_t k, std::int64_t l) const {
    return i + j * stride_[1] + k * stride_[2] + l * stride_[3];
  }
  std::int64_t offset(int corner) const {
    std::int64_t o = 0;
    for (std::size_t a = 0; a < 4; ++a)
      if (corner & (1 << a)) o += stride_[a];
    return o;
  }
  double value(std::int64_t g) const { return values_[static_cast<std::size_t>(g)]; }
  Vec4 point(std::int64_t g) const {
    Vec4 p;
    for (std::size_t a = 0; a < 4; ++a) {
      p[a] = lo_[a] + h_[a] * static_cast<double>(g % n_);
      g /= n_;
    }
    return p;
  }

  // The shared vertex where f crosses zero on the grid edge (a, b).
  std::uint32_t edge_vertex(std::int64_t a, std::int64_t b) {
    if (a > b) std::swap(a, b);
    const auto key = static_cast<std::uint64_t>(a) * values_.size() + static_cast<std::uint64_t>(b);
    const auto [it, added] = edges_.try_emplace(key, static_cast<std::uint32_t>(mesh_.vertices.size()));
    if (added) {
      const double fa = value(a), fb = value(b);
      const double s = std::clamp(fa / (fa - fb), kEdgeClamp, 1.0 - kEdgeClamp);
      const Vec4 pa = point(a);
      mesh_.vertices.push_back(pa + s * (point(b) - pa));
    }
    return it->second;
  }

  // Orientation is decided combinatorially, never from a close call on the cell's coordinates.
  // Write each cell vertex as (1 - s) X + s Y on its pentatope edge (X, Y) and take F = few[0] (the
  // lone vertex of the tetrahedron case, the apex of the prism's bottom triangle) as reference. The
  // 5x5 determinant of the barycentric rows of (cell vertices, F) is multilinear in the rows, so it
  // expands into one term per choice of an edge end for every row, nonzero only when the choices
  // and F are the five pentatope vertices. Rows on F's edges must take their far ends (F is
  // taken); in a prism a top vertex whose bottom partner is in the cell must then take few[1],
  // and a cell never holds both ends of two vertical prism edges (those span a quad face), so one
  // choice remains for every cell of either split. The determinant is thus a single monomial,
  // +-prod(s or 1 - s) times the pentatope's volume: which side of F a cell faces does not depend
  // on where along their edges its vertices sit, even kEdgeClamp-clamped ones. It is evaluated
  // here at the edge midpoints, exactly, in doubled integer grid coordinates (the box's axis
  // scaling only multiplies it by sign(h0 h1 h2 h3)). For unclamped vertices a cell lies in the
  // interpolant's zero set, so facing away from the inside is facing along the gradient: outwards.
  // Testing each cell's own normal against the interpolant's gradient instead fails where grid
  // values are at or near zero: clamped vertices sit up to kEdgeClamp of an edge off the zero set,
  // and the tiny cells around such a grid point then have normals far from the gradient.
  using Local = std::array<std::int64_t, 4>;
  void add_cell(Cell c, const std::array<std::array<int, 2>, 4>& edges, const std::array<Local, 5>& corner, int reference,
                bool reference_inside) {
    std::array<Local, 4> m{};  // doubled midpoints of the cell's edges
    for (std::size_t k = 0; k < 4; ++k)
      for (std::size_t a = 0; a < 4; ++a)
        m[k][a] = corner[static_cast<std::size_t>(edges[k][0])][a] + corner[static_cast<std::size_t>(edges[k][1])][a];
    std::array<Local, 4> rows{};  // e1, e2, e3 and the reference relative to the first vertex
    for (std::size_t a = 0; a < 4; ++a) {
      for (std::size_t k = 0; k < 3; ++k) rows[k][a] = m[k + 1][a] - m[0][a];
      rows[3][a] = 2 * corner[static_cast<std::size_t>(reference)][a] - m[0][a];
    }
    // dot(cross(e1, e2, e3), r) = det(r, e1, e2, e3) = -det(e1, e2, e3, r).
    const std::int64_t side = -det4(rows) * axis_sign_;
    if (side == 0) throw std::logic_error("marching: a cell parallel to its reference vertex");  // excluded above
    // The normal must point away from an inside reference and towards an outside one.
    if ((side > 0) == reference_inside) std::swap(c[2], c[3]);
    mesh_.cells.push_back(c);
  }

  static std::int64_t det4(const std::array<Local, 4>& r) {
    // Laplace expansion along the first row; entries are small integers, so this is exact.
    std::int64_t d = 0;
    for (std::size_t j = 0; j < 4; ++j) {
      std::array<std::size_t, 3> col{};
      std::size_t n = 0;
      for (std::size_t k = 0; k < 4; ++k)
        if (k != j) col[n++] = k;
      const std::int64_t minor = r[1][col[0]] * (r[2][col[1]] * r[3][col[2]] - r[2][col[2]] * r[3][col[1]]) -
                                 r[1][col[1]] * (r[2][col[0]] * r[3][col[2]] - r[2][col[2]] * r[3][col[0]]) +
                                 r[1][col[2]] * (r[2][col[0]] * r[3][col[1]] - r[2][col[1]] * r[3][col[0]]);
      d += (j % 2 == 0 ? 1 : -1) * r[0][j] * minor;
    }
    return d;
  }

  void pentatope(std::int64_t base, const Perm& perm) {
    std::array<std::int64_t, 5> g{};
    std::array<Local, 5> corner{};  // the Kuhn path in local integer coordinates
    int bits = 0;
    g[0] = base;
    for (std::size_t k = 0; k < 4; ++k) {
      bits |= 1 << perm[k];
      g[k + 1] = base + offset(bits);
      corner[k + 1] = corner[k];
      corner[k + 1][static_cast<std::size_t>(perm[k])] = 1;
    }
    std::array<int, 5> in{}, out{};
    int n_in = 0, n_out = 0;
    for (int k = 0; k < 5; ++k)
      (value(g[static_cast<std::size_t>(k)]) < 0 ? in[static_cast<std::size_t>(n_in++)]
                                                 : out[static_cast<std::size_t>(n_out++)]) = k;
    if (n_in == 0 || n_out == 0) return;
    const bool few_inside = n_in < n_out;
    const auto& few = few_inside ? in : out;
    const auto& many = few_inside ? out : in;
    const auto gv = [&](int k) { return g[static_cast<std::size_t>(k)]; };
    if (std::min(n_in, n_out) == 1) {
      std::array<std::array<int, 2>, 4> edges{};
      Cell c{};
      for (std::size_t i = 0; i < 4; ++i) {
        edges[i] = {few[0], many[i]};
        c[i] = edge_vertex(gv(few[0]), gv(many[i]));
      }
      add_cell(c, edges, corner, few[0], few_inside);
      return;
    }
    // Prism: vertex i + 3 lies above vertex i, bottom triangle around few[0], top around few[1].
    std::array<std::uint32_t, 6> v{};
    std::array<std::array<int, 2>, 6> edge{};
    for (std::size_t i = 0; i < 3; ++i) {
      edge[i] = {few[0], many[i]};
      edge[i + 3] = {few[1], many[i]};
      v[i] = edge_vertex(gv(few[0]), gv(many[i]));
      v[i + 3] = edge_vertex(gv(few[1]), gv(many[i]));
    }
    static constexpr int kRotate[6][6] = {{0, 1, 2, 3, 4, 5}, {1, 2, 0, 4, 5, 3}, {2, 0, 1, 5, 3, 4},
                                          {3, 5, 4, 0, 2, 1}, {4, 3, 5, 1, 0, 2}, {5, 4, 3, 2, 1, 0}};
    const auto lowest = static_cast<std::size_t>(std::min_element(v.begin(), v.end()) - v.begin());
    std::array<std::size_t, 6> r{};  // prism vertex numbers, rotated so that r[0] holds the lowest index
    for (std::size_t i = 0; i < 6; ++i) r[i] = static_cast<std::size_t>(kRotate[lowest][i]);
    const auto add = [&](std::size_t a, std::size_t b, std::size_t c, std::size_t d) {
      add_cell({v[r[a]], v[r[b]], v[r[c]], v[r[d]]}, {edge[r[a]], edge[r[b]], edge[r[c]], edge[r[d]]}, corner, few[0],
               few_inside);
    };
    if (std::min(v[r[1]], v[r[5]]) < std::min(v[r[2]], v[r[4]])) {
      add(0, 1, 2, 5);
      add(0, 1, 5, 4);
    } else {
      add(0, 1, 2, 4);
      add(0, 4, 2, 5);
    }
    add(0, 4, 5, 3);
  }

  Vec4 lo_;
  Vec4 h_;
  std::int64_t cells_, n_;
  std::int64_t axis_sign_ = 1;  // sign of h0 h1 h2 h3: a mirrored box mirrors every orientation
  std::array<std::int64_t, 4> stride_{};
  std::vector<double> values_;
  std::unordered_map<std::uint64_t, std::uint32_t> edges_;
  TetMesh mesh_;
};

double norm2(double a, double b) {
  return std::sqrt(a * a + b * b);
}
double max_abs(const Vec4& p) {
  return std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z), std::abs(p.w)});
}

// A cell of the open floor or pyramid mesh, oriented so its normal has a positive component along `out`.
void add_oriented(TetMesh& mesh, Cell c, const Vec4& out) {
  const auto& v = mesh.vertices;
  if (dot(cross(v[c[1]] - v[c[0]], v[c[2]] - v[c[0]], v[c[3]] - v[c[0]]), out) < 0) std::swap(c[2], c[3]);
  mesh.cells.push_back(c);
}

std::uint32_t add_vertex(TetMesh& mesh, const Vec4& p) {
  mesh.vertices.push_back(p);
  return static_cast<std::uint32_t>(mesh.vertices.size() - 1);
}

// The thesis's scene made into real 4D surfaces: two tetrahedral pyramids (each the boundary of a
// pentatope without its base), mirror images under x -> -x, standing on a floor hyperplane w = 0
// that faces the camera at w < 0. A correct AO darkens both sides alike.
TetMesh two_tetrahedra() {
  TetMesh mesh;
  const Vec4 toward_camera{0, 0, 0, -1};
  // Floor: the cube [-2, 2]^3 at w = 0, split into its 6 Kuhn tetrahedra.
  std::array<std::uint32_t, 8> corner{};
  for (int c = 0; c < 8; ++c)
    corner[static_cast<std::size_t>(c)] = add_vertex(mesh, {c & 1 ? 2.0 : -2.0, c & 2 ? 2.0 : -2.0, c & 4 ? 2.0 : -2.0, 0.0});
  std::array<int, 3> perm{0, 1, 2};
  do {
    int m = 0;
    Cell cell{corner[0], 0, 0, 0};
    for (std::size_t k = 0; k < 3; ++k) {
      m |= 1 << perm[k];
      cell[k + 1] = corner[static_cast<std::size_t>(m)];
    }
    add_oriented(mesh, cell, toward_camera);
  } while (std::next_permutation(perm.begin(), perm.end()));
  for (const double side : {-1.0, 1.0}) {
    const Vec4 centre{side, 0, 0, 0};
    const double s = 0.5;
    // Mirroring x maps one pyramid onto the other vertex by vertex.
    const std::array<Vec4, 4> base{Vec4{side * s, s, s, 0}, Vec4{side * s, -s, -s, 0}, Vec4{-side * s, s, -s, 0},
                                   Vec4{-side * s, -s, s, 0}};
    std::array<std::uint32_t, 4> b{};
    for (std::size_t i = 0; i < 4; ++i) b[i] = add_vertex(mesh, centre + base[i]);
    const Vec4 apex_pos = centre + Vec4{0, 0, 0, -1.0};
    const std::uint32_t apex = add_vertex(mesh, apex_pos);
    const Vec4 solid_centre = (4.0 * centre + apex_pos) / 5.0;
    for (std::size_t skip = 0; skip < 4; ++skip) {
      Cell c{apex, 0, 0, 0};
      std::size_t k = 1;
      Vec4 face_centre = apex_pos;
      for (std::size_t i = 0; i < 4; ++i)
        if (i != skip) {
          c[k++] = b[i];
          face_centre += mesh.vertices[b[i]];
        }
      add_oriented(mesh, c, face_centre / 4.0 - solid_centre);
    }
  }
  return mesh;
}

}  // namespace

TetMesh march(const Field& f, const Vec4& lo, const Vec4& hi, int cells) {
  if (cells < 1) throw std::invalid_argument("marching needs at least one cell per axis");
  return Marcher(f, lo, hi, cells).run();
}

const std::vector<std::string>& shape_names() {
  static const std::vector<std::string> names{"hypersphere", "tesseract", "indented-tesseract",
                                              "duocylinder", "torus",     "two-tetrahedra"};
  return names;
}

std::string shape_list() {
  std::string list;
  for (const std::string& name : shape_names()) list += (list.empty() ? "" : ", ") + name;
  return list;
}

TetMesh make_shape(const std::string& name, int grid) {
  // Boxes are slightly asymmetric so that no grid point falls exactly on a flat face.
  const Vec4 lo{-1.13, -1.13, -1.13, -1.13}, hi{1.11, 1.11, 1.11, 1.11};
  if (name == "hypersphere") return march([](const Vec4& p) { return length(p) - 1.0; }, lo, hi, grid);
  if (name == "tesseract") return march([](const Vec4& p) { return max_abs(p) - 0.8; }, lo, hi, grid);
  if (name == "indented-tesseract")
    // A ball of radius 0.6 bites 0.3 deep into the -w face, the face the camera looks at.
    return march([](const Vec4& p) { return std::max(max_abs(p) - 0.8, 0.6 - length(p - Vec4{0, 0, 0, -1.1})); }, lo, hi, grid);
  if (name == "duocylinder")
    return march([](const Vec4& p) { return std::max(norm2(p.x, p.y), norm2(p.z, p.w)) - 0.8; }, lo, hi, grid);
  if (name == "torus")
    // Spheritorus: the points within 0.35 of the circle of radius 0.7 in the xy-plane (S^1 x S^2).
    return march([](const Vec4& p) { return std::sqrt(std::pow(norm2(p.x, p.y) - 0.7, 2) + p.z * p.z + p.w * p.w) - 0.35; }, lo,
                 hi, grid);
  if (name == "two-tetrahedra") return two_tetrahedra();
  throw std::invalid_argument("unknown shape '" + name + "', expected one of: " + shape_list());
}

}  // namespace ao4d
