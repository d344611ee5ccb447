// Marching simplices: closed, consistently oriented 3-manifolds with outward normals.
#include "ao4d/shapes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <ostream>
#include <set>
#include <utility>

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

void PrintTo(const Expected& e, std::ostream* os) { *os << e.shape << " at grid " << e.grid; }

class ClosedShape : public testing::TestWithParam<Expected> {};

TEST_P(ClosedShape, IsAClosedConsistentlyOrientedManifoldWithOutwardNormals) {
    const Expected e = GetParam();
    const TetMesh mesh = make_shape(e.shape, e.grid);
    ASSERT_GT(mesh.cells.size(), 1000u);

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
        // Closed: every triangle bounds exactly two cells; oriented: they induce opposite signs.
        ASSERT_EQ(signs.size(), 2u) << t[0] << ' ' << t[1] << ' ' << t[2];
        ASSERT_EQ(signs[0], -signs[1]) << t[0] << ' ' << t[1] << ' ' << t[2];
    }
    // Every closed 3-manifold has Euler characteristic 0.
    const auto chi = static_cast<long>(mesh.vertices.size()) - static_cast<long>(edges.size()) +
                     static_cast<long>(faces.size()) - static_cast<long>(mesh.cells.size());
    EXPECT_EQ(chi, 0);

    for (std::size_t i = 0; i < mesh.cells.size(); ++i) ASSERT_GT(length(cell_normal(mesh, i)), 0.0) << "cell " << i;
    // Outward orientation makes the enclosed volume positive; linear interpolation on a 10^4 grid
    // cuts corners and edges, which the 15% allows for.
    EXPECT_NEAR(enclosed_volume(mesh), e.volume, 0.15 * e.volume);
}

constexpr double kPi = std::numbers::pi;
INSTANTIATE_TEST_SUITE_P(Shapes, ClosedShape,
                         testing::Values(Expected{"hypersphere", kPi * kPi / 2},       // pi^2 r^4 / 2
                                         Expected{"tesseract", std::pow(1.6, 4)},      // edge 1.6
                                         // Less the 4-ball cap Int_0.3^0.6 (4 pi / 3) (0.36 - u^2)^(3/2) du = 0.0809575.
                                         Expected{"indented-tesseract", std::pow(1.6, 4) - 0.0809575},
                                         Expected{"duocylinder", std::pow(kPi * 0.64, 2)},  // (pi r^2)^2
                                         Expected{"torus", 2 * kPi * 0.7 * 4.0 / 3.0 * kPi * std::pow(0.35, 3), 16}),  // Pappus
                         [](const testing::TestParamInfo<Expected>& param) {
                             std::string name = param.param.shape;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });

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
