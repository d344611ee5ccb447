// The plain-text mesh and points formats: round trip and errors that name file, line and expectation.
#include "ao4d/mesh.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

namespace ao4d {
namespace {

std::string parse_error(const std::string& text) {
  std::istringstream in(text);
  try {
    parse_mesh(in, "scene.tet4");
  } catch (const ParseError& e) {
    return e.what();
  }
  return "no error";
}

TEST(MeshFormat, ParsesCommentsBlanksAndOptionalValues) {
  std::istringstream in("# a cell\n\nv 0 0 0 0 0.5\nv 1 0 0 0 1\nv 0 1 0 0 0   # trailing comment\nv 0 0 1 0 0.25\nt 1 2 3 4\n");
  std::vector<double> values;
  const TetMesh mesh = parse_mesh(in, "x", &values);
  ASSERT_EQ(mesh.vertices.size(), 4u);
  ASSERT_EQ(mesh.cells.size(), 1u);
  EXPECT_EQ(mesh.cells[0], (Cell{0, 1, 2, 3}));
  EXPECT_EQ(values, (std::vector<double>{0.5, 1, 0, 0.25}));
}

TEST(MeshFormat, RoundTripsThroughAFile) {
  TetMesh mesh;
  mesh.vertices = {{0.1, -2, 3e-7, 4}, {1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 1.0 / 3.0}, {5, 5, 5, 5}};
  mesh.cells = {{0, 1, 2, 3}, {4, 3, 2, 1}};
  const std::vector<double> values{0, 0.25, 0.5, 0.75, 1};
  const auto file = std::filesystem::path(AO4D_TEST_OUTPUT_DIR) / "roundtrip.tet4";
  write_mesh(file, mesh, &values);
  std::vector<double> read_values;
  const TetMesh back = read_mesh(file, &read_values);
  EXPECT_EQ(back.vertices, mesh.vertices);
  EXPECT_EQ(back.cells, mesh.cells);
  EXPECT_EQ(read_values, values);
}

TEST(MeshFormat, ErrorsNameTheFileTheLineAndWhatWasExpected) {
  EXPECT_EQ(parse_error("v 0 0 0\n"), "scene.tet4:1: expected 'v x y z w' with an optional value, got 3 numbers");
  EXPECT_EQ(parse_error("v 0 0 0 0\nv 0 0 zero 0\n"), "scene.tet4:2: expected a finite number for z, got 'zero'");
  EXPECT_EQ(parse_error("v 0 0 0 nan\n"), "scene.tet4:1: expected a finite number for w, got 'nan'");
  EXPECT_EQ(parse_error("v 0 0 0 0\nt 1 2 3\n"), "scene.tet4:2: expected 't a b c d' (four 1-based vertex indices)");
  EXPECT_EQ(parse_error("t 0 1 2 3\n"), "scene.tet4:1: expected a 1-based vertex index, got '0'");
  EXPECT_EQ(parse_error("t 1 2 2 3\n"), "scene.tet4:1: expected four distinct vertex indices, vertex 2 repeats");
  EXPECT_EQ(parse_error("v 0 0 0 0\n# c\nt 1 2 3 4\n"), "scene.tet4:3: vertex index 2 is out of range (the file has 1 vertices)");
  EXPECT_EQ(parse_error("f 1 2 3\n"), "scene.tet4:1: expected a 'v' or 't' line, got 'f'");
  EXPECT_EQ(parse_error("v 0 0 0 0\n"), "scene.tet4: expected at least one 't' line, found none");
}

TEST(MeshFormat, MissingFileIsNamed) {
  try {
    read_mesh("/nonexistent/dir/mesh.tet4");
    FAIL();
  } catch (const ParseError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/dir/mesh.tet4: cannot open the mesh file");
  }
}

TEST(PointsFormat, ParsesAndNormalisesNormals) {
  std::istringstream in("0 0 0 0  0 0 0 2\n\n1 2 3 4 1 0 0 0\n");
  const auto points = parse_points(in, "p.txt");
  ASSERT_EQ(points.size(), 2u);
  EXPECT_EQ(points[0].normal, (Vec4{0, 0, 0, 1}));
  EXPECT_EQ(points[1].position, (Vec4{1, 2, 3, 4}));
}

TEST(PointsFormat, ErrorsNameTheFileTheLineAndTheField) {
  auto error = [](const std::string& text) {
    std::istringstream in(text);
    try {
      parse_points(in, "p.txt");
    } catch (const ParseError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error("0 0 0 0 0 0 0\n"), "p.txt:1: expected 8 numbers 'px py pz pw nx ny nz nw', got 7");
  EXPECT_EQ(error("\n0 0 0 0 0 0 x 1\n"), "p.txt:2: expected a finite number for nz, got 'x'");
  EXPECT_EQ(error("0 0 0 0 0 0 0 0\n"), "p.txt:1: expected a non-zero normal (nx ny nz nw)");
}

}  // namespace
}  // namespace ao4d
