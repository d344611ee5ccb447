// Marching simplices: closed, consistently oriented 3-manifolds with outward normals.
#include "ao4d/sampling.hpp"
#include "ao4d/shapes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <ostream>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace ao4d {
namespace {

using Triangle = std::array<std::uint32_t, 3>;

// The boundary of the oriented cell (a, b, c, d) is (b c d) - (a c d) + (a b d) - (a b c); a face's
// sign relative to its sorted vertices is that sign times the parity of the sorting permutation.
std::vector<std::pair<Triangle, int>> oriented_faces(const Cell& c) {
  std::vector<std::pair<Triangle, int>> faces;
  for (std::size_t skip = 0; skip < 4; ++skip) {
    Triangle t{};
    std::size_t k = 0;
    for (std::size_t i = 0; i < 4; ++i)
      if (i != skip) t[k++] = c[i];
    int sign = skip % 2 == 0 ? 1 : -1;
    for (std::size_t i = 0; i < 3; ++i)  // bubble sort, counting swaps
      for (std::size_t j = 0; j + 1 < 3 - i; ++j)
        if (t[j] > t[j + 1]) {
          std::swap(t[j], t[j + 1]);
          sign = -sign;
        }
    faces.emplace_back(t, sign);
  }
  return faces;
}

// 4-volume enclosed by an oriented closed mesh, by the divergence theorem: (1/4) Int x . n dS.
double enclosed_volume(const TetMesh& mesh) {
  double sum = 0;
  for (std::size_t i = 0; i < mesh.cells.size(); ++i) {
    Vec4 centroid;
    for (std::uint32_t v : mesh.cells[i]) centroid += 0.25 * mesh.vertices[v];
    sum += dot(centroid, cell_normal(mesh, i)) / 6.0;  // |cell_normal| is 6 times the 3-volume
  }
  return sum / 4.0;
}

struct Expected {
  const char* shape;
  double volume;  // analytic 4-volume of the object
  int grid = 10;  // marching cells per axis: fine enough for the shape's thinnest part
};

void PrintTo(const Expected& e, std::ostream* os) {
  *os << e.shape << " at grid " << e.grid;
}

// Closed: every triangle bounds exactly two cells; oriented: they induce opposite signs on it; a
// 3-manifold: Euler characteristic 0 (true of every closed odd-dimensional manifold); no flat cells.
void expect_closed_oriented_manifold(const TetMesh& mesh) {
  std::map<Triangle, std::vector<int>> faces;
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const Cell& c : mesh.cells) {
    for (std::size_t i = 0; i < 4; ++i)
      for (std::size_t j = i + 1; j < 4; ++j) {
        ASSERT_NE(c[i], c[j]);
        edges.insert(std::minmax(c[i], c[j]));
      }
    for (const auto& [t, sign] : oriented_faces(c)) faces[t].push_back(sign);
  }
  for (const auto& [t, signs] : faces) {
    ASSERT_EQ(signs.size(), 2u) << t[0] << ' ' << t[1] << ' ' << t[2];
    ASSERT_EQ(signs[0], -signs[1]) << t[0] << ' ' << t[1] << ' ' << t[2];
  }
  const auto chi = static_cast<long>(mesh.vertices.size()) - static_cast<long>(edges.size()) + static_cast<long>(faces.size()) -
                   static_cast<long>(mesh.cells.size());
  EXPECT_EQ(chi, 0);
  for (std::size_t i = 0; i < mesh.cells.size(); ++i) ASSERT_GT(length(cell_normal(mesh, i)), 0.0) << "cell " << i;
}

class ClosedShape : public testing::TestWithParam<Expected> {};

TEST_P(ClosedShape, IsAClosedConsistentlyOrientedManifoldWithOutwardNormals) {
  const Expected e = GetParam();
  const TetMesh mesh = make_shape(e.shape, e.grid);
  ASSERT_GT(mesh.cells.size(), 1000u);
  expect_closed_oriented_manifold(mesh);
  if (HasFatalFailure()) return;
  // Outward orientation makes the enclosed volume positive; linear interpolation on a 10^4 grid
  // cuts corners and edges, which the 15% allows for.
  EXPECT_NEAR(enclosed_volume(mesh), e.volume, 0.15 * e.volume);
}

constexpr double kPi = std::numbers::pi;
INSTANTIATE_TEST_SUITE_P(Shapes, ClosedShape,
                         testing::Values(Expected{"hypersphere", kPi* kPi / 2},    // pi^2 r^4 / 2
                                         Expected{"tesseract", std::pow(1.6, 4)},  // edge 1.6
                                         // Less the 4-ball cap Int_0.3^0.6 (4 pi / 3) (0.36 - u^2)^(3/2) du = 0.0809575.
                                         Expected{"indented-tesseract", std::pow(1.6, 4) - 0.0809575},
                                         Expected{"duocylinder", std::pow(kPi * 0.64, 2)},  // (pi r^2)^2
                                         Expected{"torus", 2 * kPi * 0.7 * 4.0 / 3.0 * kPi* std::pow(0.35, 3), 16}),  // Pappus
                         [](const testing::TestParamInfo<Expected>& param) {
                           std::string name = param.param.shape;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// The indent is small next to the marching error of the tesseract itself (at grid 10 linear
// interpolation bevels the tesseract's edges and corners by about 0.27, three times the indent), so
// the 15% above cannot see it. Compared at the same grid, that error cancels: both fields are equal
// at every grid point away from the cap, so the two meshes coincide there and their volumes differ
// by the marched cap alone.
TEST(IndentedTesseract, EnclosesTheTesseractLessTheBallsCap) {
  const int grid = 10;
  const double h = 2.24 / grid;  // make_shape's box is [-1.13, 1.11]^4
  const double cap = 0.0809575;  // Int_0.3^0.6 (4 pi / 3) (0.36 - u^2)^(3/2) du, as above
  const TetMesh plain = make_shape("tesseract", grid), indented = make_shape("indented-tesseract", grid);
  const double difference = enclosed_volume(plain) - enclosed_volume(indented);
  // Linear interpolation of the ball's distance function along a grid edge misplaces a vertex by
  // at most about the chord sag h^2 / (8 R) (0.0105 here), so the marched cap is off by at most its
  // curved boundary's 3-volume (4 pi R^3 Int_0^{pi/3} sin^2 = 0.834) times that: 0.0087, a tenth
  // of the cap.
  const double tolerance = 0.834 * h * h / (8 * 0.6);
  EXPECT_NEAR(difference, cap, tolerance);
  // The cap is all the difference: the meshes share every vertex away from it. A vertex moves only
  // if its grid edge (at most 2h long) has an end q where the ball's term wins, and as the field is
  // 1-Lipschitz and changes sign along the edge, such a q lies within 0.6 + 2h of the ball's centre.
  std::set<std::array<double, 4>> shared;
  for (const Vec4& v : plain.vertices) shared.insert({v.x, v.y, v.z, v.w});
  std::size_t moved = 0;
  for (const Vec4& v : indented.vertices)
    if (!shared.contains({v.x, v.y, v.z, v.w})) {
      ++moved;
      EXPECT_LT(length(v - Vec4{0, 0, 0, -1.1}), 0.6 + 4 * h) << v.x << ' ' << v.y << ' ' << v.z << ' ' << v.w;
    }
  EXPECT_GT(moved, 0u);
  EXPECT_LT(moved, indented.vertices.size() / 10);  // 858 of 19892
}

// Marching random fields on a small grid, many grid values exactly 0 or within 1e-12 of it: the
// vertices on their edges are clamped off the zero set, the cells around them are tiny, and an
// orientation read from their coordinates would be a close call.
TetMesh march_random_field(std::uint64_t seed, bool near_zero, std::vector<double>& values) {
  constexpr int n = 4, m = n + 1;
  Rng rng(seed);
  values.assign(m * m * m * m, 0.0);
  for (std::size_t g = 0; g < values.size(); ++g) {
    std::size_t rest = g;
    bool boundary = false;
    for (int a = 0; a < 4; ++a, rest /= m) boundary = boundary || rest % m == 0 || rest % m == n;
    const double u = rng.uniform();
    const double sign = rng.uniform() < 0.5 ? -1.0 : 1.0;
    if (boundary)
      values[g] = 1.0;  // outside, so the surface is closed
    else if (near_zero && u < 0.3)
      values[g] = 0.0;
    else if (near_zero && u < 0.45)
      values[g] = sign * 1e-12 * rng.uniform();
    else
      values[g] = sign * (0.1 + 0.9 * rng.uniform());
  }
  const auto field = [&](const Vec4& p) {
    std::size_t g = 0;
    for (std::size_t a = 4; a-- > 0;) g = g * m + static_cast<std::size_t>(std::lround(p[a]));
    return values[g];
  };
  return march(field, {0, 0, 0, 0}, {n, n, n, n}, n);
}

TEST(Marching, RandomFieldsWithZerosGiveClosedConsistentlyOrientedManifolds) {
  std::size_t cells = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    std::vector<double> values;
    const TetMesh mesh = march_random_field(seed, true, values);
    cells += mesh.cells.size();
    SCOPED_TRACE("seed " + std::to_string(seed));
    expect_closed_oriented_manifold(mesh);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(cells, 40u * 1000u);
}

// With grid values away from zero no vertex is clamped, each cell lies in the zero set of the
// linear interpolant on its pentatope, and outwards is exactly along that interpolant's gradient.
TEST(Marching, CellsOfRandomFieldsFaceAlongTheInterpolantsGradient) {
  constexpr int m = 5;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    std::vector<double> values;
    const TetMesh mesh = march_random_field(seed, false, values);
    ASSERT_GT(mesh.cells.size(), 1000u);
    const auto value = [&](const std::array<int, 4>& c) {
      return values[static_cast<std::size_t>(c[0] + m * (c[1] + m * (c[2] + m * c[3])))];
    };
    for (std::size_t i = 0; i < mesh.cells.size(); ++i) {
      // The cell's pentatope holds its centroid; in the Kuhn triangulation that is the one
      // whose path from the hypercube's corner takes the axes by decreasing local coordinate.
      Vec4 centroid;
      for (std::uint32_t v : mesh.cells[i]) centroid += 0.25 * mesh.vertices[v];
      std::array<int, 4> corner{}, axes{0, 1, 2, 3};
      std::array<double, 4> local{};
      for (std::size_t a = 0; a < 4; ++a) {
        corner[a] = static_cast<int>(std::floor(centroid[a]));
        local[a] = centroid[a] - corner[a];
      }
      std::sort(axes.begin(), axes.end(),
                [&](int a, int b) { return local[static_cast<std::size_t>(a)] > local[static_cast<std::size_t>(b)]; });
      Vec4 gradient;
      for (const int a : axes) {
        std::array<int, 4> next = corner;
        ++next[static_cast<std::size_t>(a)];
        gradient[static_cast<std::size_t>(a)] = value(next) - value(corner);
        corner = next;
      }
      // Parallel, not just on the same side: the cell lies in the interpolant's zero set.
      ASSERT_GT(dot(normalize(cell_normal(mesh, i)), normalize(gradient)), 1 - 1e-9) << "seed " << seed << ", cell " << i;
    }
  }
}

// The thesis's scene: a floor facing the camera (at w < 0) and two pyramids, each the boundary of a
// pentatope less its base, with outward normals, mirror images of each other under x -> -x.
TEST(TwoTetrahedra, FloorFacesTheCameraAndThePyramidsFaceOutwards) {
  const TetMesh mesh = make_shape("two-tetrahedra", 0);
  const auto normals = cell_normals(mesh);
  std::map<std::uint32_t, std::set<std::uint32_t>> pyramids;  // apex -> every vertex of its pentatope
  std::size_t floor_cells = 0;
  for (std::size_t i = 0; i < mesh.cells.size(); ++i) {
    const Cell& c = mesh.cells[i];
    const auto apex = std::find_if(c.begin(), c.end(), [&](std::uint32_t v) { return mesh.vertices[v].w < -0.5; });
    if (apex == c.end()) {
      ++floor_cells;
      EXPECT_EQ(normals[i], (Vec4{0, 0, 0, -1})) << "cell " << i;
    } else {
      pyramids[*apex].insert(c.begin(), c.end());
    }
  }
  EXPECT_EQ(floor_cells, 6u);
  ASSERT_EQ(pyramids.size(), 2u);
  std::map<std::uint32_t, std::vector<Vec4>> side_normals;
  for (std::size_t i = 0; i < mesh.cells.size(); ++i) {
    const Cell& c = mesh.cells[i];
    for (const auto& [apex, vertices] : pyramids) {
      if (std::find(c.begin(), c.end(), apex) == c.end()) continue;
      ASSERT_EQ(vertices.size(), 5u);
      Vec4 solid, face;
      for (std::uint32_t v : vertices) solid += 0.2 * mesh.vertices[v];
      for (std::uint32_t v : c) face += 0.25 * mesh.vertices[v];
      // Outward: away from the pentatope's centroid. The cell through the apex and a face of
      // the base (a regular tetrahedron of inradius r = 0.5 / sqrt(3), at height 1 below the
      // apex) has the normal (u, -r) / sqrt(1 + r^2), u the face's outward unit normal in 3D.
      EXPECT_GT(dot(normals[i], face - solid), 0.0) << "cell " << i;
      const double r = 0.5 / std::sqrt(3.0);
      EXPECT_NEAR(normals[i].w, -r / std::sqrt(1 + r * r), 1e-12) << "cell " << i;
      side_normals[apex].push_back(normals[i]);
    }
  }
  // Mirror images: x -> -x maps the set of side normals of one pyramid onto the other's.
  ASSERT_EQ(side_normals.size(), 2u);
  const auto& left = side_normals.begin()->second;
  const auto& right = side_normals.rbegin()->second;
  ASSERT_EQ(left.size(), 4u);
  ASSERT_EQ(right.size(), 4u);
  for (const Vec4& n : left) {
    const Vec4 mirrored{-n.x, n.y, n.z, n.w};
    EXPECT_TRUE(std::any_of(right.begin(), right.end(), [&](const Vec4& m) { return length(m - mirrored) < 1e-12; }))
        << n.x << ' ' << n.y << ' ' << n.z << ' ' << n.w;
  }
}

TEST(Hypersphere, NormalsPointAwayFromTheCentreAndVerticesLieOnTheSphere) {
  const TetMesh mesh = make_shape("hypersphere", 8);
  const auto normals = cell_normals(mesh);
  for (std::size_t i = 0; i < mesh.cells.size(); ++i) {
    Vec4 centroid;
    for (std::uint32_t v : mesh.cells[i]) centroid += 0.25 * mesh.vertices[v];
    ASSERT_GT(dot(normals[i], normalize(centroid)), 0.5) << "cell " << i;
  }
  // Vertices come from linear interpolation along grid edges of length h = 0.28; the chord error
  // of |x| - 1 is about h^2 / 2 = 0.04.
  for (const Vec4& v : mesh.vertices) ASSERT_NEAR(length(v), 1.0, 0.05);
}

TEST(Shapes, UnknownNamesListTheValidOnes) {
  try {
    make_shape("klein-bottle", 4);
    FAIL() << "expected an exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("klein-bottle"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("duocylinder"), std::string::npos);
  }
}

}  // namespace
}  // namespace ao4d
