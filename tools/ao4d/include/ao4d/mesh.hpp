// Tetrahedral meshes in R^4 (the boundary of a 4D object) and their plain-text file format.
#pragma once

#include "ao4d/vec4.hpp"

#include <array>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <vector>

namespace ao4d {

using Cell = std::array<std::uint32_t, 4>;

// A cell (A, B, C, D) is oriented so that cross(B-A, C-A, D-A) points out of the object; for an
// open mesh it points to the side the cell is lit from.
struct TetMesh {
    std::vector<Vec4> vertices;
    std::vector<Cell> cells;
};

// Unnormalised outward normal of one cell; its length is 6 times the cell's 3-volume.
Vec4 cell_normal(const TetMesh& mesh, std::size_t cell);
// Unit normals of every cell; zero for degenerate (flat) cells.
std::vector<Vec4> cell_normals(const TetMesh& mesh);
// Unit vertex normals: volume-weighted average of the incident cells' normals.
std::vector<Vec4> vertex_normals(const TetMesh& mesh);

// Bad input: the message names the file, the line and what was expected there.
class ParseError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Format (documented in tools/ao4d/README.md): '#' comments and blank lines are ignored,
// `v x y z w [value]` adds a vertex, `t a b c d` a cell with 1-based vertex indices.
// The optional per-vertex value (AO on output) is returned in `values` when asked for.
TetMesh read_mesh(const std::filesystem::path& file, std::vector<double>* values = nullptr);
TetMesh parse_mesh(std::istream& in, const std::string& name, std::vector<double>* values = nullptr);
void write_mesh(const std::filesystem::path& file, const TetMesh& mesh, const std::vector<double>* values = nullptr);

// One query point with its normal, as read from a `--points` file (`px py pz pw nx ny nz nw`).
struct OrientedPoint {
    Vec4 position;
    Vec4 normal;
};
std::vector<OrientedPoint> read_points(const std::filesystem::path& file);
std::vector<OrientedPoint> parse_points(std::istream& in, const std::string& name);

}  // namespace ao4d
