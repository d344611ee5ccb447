// Small scenes with known answers, shared by the ao4d tests.
#pragma once

#include "ao4d/mesh.hpp"

#include <algorithm>
#include <array>
#include <utility>

namespace ao4d::test {

// The parallelepiped corner + [0,1]^3 (u, v, w) as its 6 Kuhn tetrahedra, each oriented so that its
// normal has a positive component along `out`.
inline void add_box(TetMesh& mesh, const Vec4& corner, const Vec4& u, const Vec4& v, const Vec4& w, const Vec4& out) {
    const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
    const std::array<Vec4, 3> edges{u, v, w};
    for (int c = 0; c < 8; ++c) {
        Vec4 p = corner;
        for (std::size_t a = 0; a < 3; ++a)
            if (c & (1 << a)) p += edges[a];
        mesh.vertices.push_back(p);
    }
    std::array<int, 3> perm{0, 1, 2};
    do {
        int m = 0;
        Cell cell{first, 0, 0, 0};
        for (std::size_t k = 0; k < 3; ++k) {
            m |= 1 << perm[k];
            cell[k + 1] = first + static_cast<std::uint32_t>(m);
        }
        const Vec4& a = mesh.vertices[cell[0]];
        if (dot(cross(mesh.vertices[cell[1]] - a, mesh.vertices[cell[2]] - a, mesh.vertices[cell[3]] - a), out) < 0)
            std::swap(cell[2], cell[3]);
        mesh.cells.push_back(cell);
    } while (std::next_permutation(perm.begin(), perm.end()));
}

// The floor hyperplane w = 0 over [-size, size]^3, facing +w.
inline TetMesh floor_mesh(double size) {
    TetMesh mesh;
    add_box(mesh, {-size, -size, -size, 0}, {2 * size, 0, 0, 0}, {0, 2 * size, 0, 0}, {0, 0, 2 * size, 0}, {0, 0, 0, 1});
    return mesh;
}

// The floor plus k mutually perpendicular walls x = 0, y = 0, z = 0 (in that order) of height `size`,
// facing the positive side, which the open corner region x, y, z > 0 sees.
inline TetMesh corner_mesh(int k, double size) {
    TetMesh mesh = floor_mesh(size);
    const double s = 2 * size;
    const Vec4 up{0, 0, 0, size};
    if (k >= 1) add_box(mesh, {0, -size, -size, 0}, {0, s, 0, 0}, {0, 0, s, 0}, up, {1, 0, 0, 0});
    if (k >= 2) add_box(mesh, {-size, 0, -size, 0}, {s, 0, 0, 0}, {0, 0, s, 0}, up, {0, 1, 0, 0});
    if (k >= 3) add_box(mesh, {-size, -size, 0, 0}, {s, 0, 0, 0}, {0, s, 0, 0}, up, {0, 0, 1, 0});
    return mesh;
}

}  // namespace ao4d::test
