// The ao4d command end to end: exit codes and messages for bad input, --points output, and the
// volume mode's five files, compared with what the library computes for the same options.
#include "ao4d/render.hpp"
#include "ao4d/scene.hpp"
#include "ao4d/shapes.hpp"
#include "volume_files.hpp"

#include <gtest/gtest.h>

#include <sys/wait.h>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

using namespace ao4d;

struct Result {
  int status = -1;
  std::string output;  // stdout and stderr together
};

Result run(const std::string& args) {
  Result r;
  FILE* pipe = popen((std::string(AO4D_CLI) + " " + args + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buffer;
  while (const std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) r.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

std::filesystem::path write(const std::string& name, const std::string& text) {
  const auto file = std::filesystem::path(AO4D_TEST_OUTPUT_DIR) / name;
  std::ofstream(file) << text;
  return file;
}

// A unit cell in w = 0 facing +w, as a mesh file.
const char* kFloor = "v -1 -1 0 0\nv 3 -1 0 0\nv -1 3 0 0\nv -1 -1 3 0\nt 1 2 3 4\n";

TEST(Cli, BadMeshFailsNamingTheFileAndLine) {
  const auto mesh = write("bad.tet4", "v 0 0 0 0\nv 1 0 0 0\nt 1 2 x 4\n");
  const Result r = run("--mesh " + mesh.string() + " -o " + (mesh.parent_path() / "bad").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find(mesh.string() + ":3: expected a 1-based vertex index, got 'x'"), std::string::npos) << r.output;
}

TEST(Cli, BadPointsFailNamingTheFileAndLine) {
  const auto mesh = write("floor.tet4", kFloor);
  const auto points = write("bad.points", "0 0 0 0 0 0 0 1\n0 0 0\n");
  const Result r = run("--mesh " + mesh.string() + " --points " + points.string());
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find(points.string() + ":2: expected 8 numbers"), std::string::npos) << r.output;
}

TEST(Cli, MissingSourceOrOutputIsAUsageError) {
  EXPECT_NE(run("--rays 4").status, 0);
  EXPECT_NE(run("--shape hypersphere").status, 0);
  const Result r = run("--shape nosuch -o x");
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.output.find("unknown shape 'nosuch'"), std::string::npos) << r.output;
}

TEST(Cli, PointsModePrintsOneValuePerLine) {
  const auto mesh = write("floor.tet4", kFloor);
  // On the plane facing away from it, then 0.5 above it facing it with rays of length 1.
  const auto points = write("ok.points", "0 0 0 0 0 0 0 1\n0 0 0 0.5 0 0 0 -1\n");
  const Result r = run("--mesh " + mesh.string() + " --points " + points.string() + " --rays 4000 --radius 1 --seed 3 -q");
  ASSERT_EQ(r.status, 0) << r.output;
  double a = -1, b = -1;
  ASSERT_EQ(std::sscanf(r.output.c_str(), "%lf\n%lf\n", &a, &b), 2) << r.output;
  EXPECT_EQ(a, 0.0);
  EXPECT_GT(b, 0.0);
  EXPECT_LT(b, 0.391);  // the cell is finite, so below the infinite plane's value
}

TEST(Cli, HelpDescribesTheOptions) {
  const Result r = run("--help");
  EXPECT_EQ(r.status, 0);
  for (const char* option : {"--shape", "--mesh", "--points", "--size", "--rays", "--radius", "--seed", "--cosine"})
    EXPECT_NE(r.output.find(option), std::string::npos) << option;
}

// Volume mode runs on the thesis's scene: 8^3 voxels, 8 rays, so each run takes a moment.
constexpr const char* kVolumeArgs = "--shape two-tetrahedra --size 8 --rays 8 -q";
constexpr std::array<const char*, 5> kSuffixes{".vti", ".ao.nrrd", ".depth.nrrd", ".png", ".tet4"};

// A fresh output prefix DIR/x (DIR does not exist yet: the command creates it).
std::string fresh_prefix(const std::string& dir) {
  const auto path = std::filesystem::path(AO4D_TEST_OUTPUT_DIR) / dir;
  std::filesystem::remove_all(path);
  return (path / "x").string();
}

// What the command must compute for kVolumeArgs plus the given camera and AO options: its default
// radius is a quarter of the scene's diagonal, its default seed 1.
struct Expected {
  Volume volume;
  std::vector<double> vertex_ao;
};

Expected library_result(Projection projection, bool cosine, std::uint64_t seed) {
  const Scene scene(make_shape("two-tetrahedra", 10));
  AoParams params;
  params.radius = 0.25 * scene.diagonal();
  params.rays = 8;
  params.seed = seed;
  params.cosine = cosine;
  CameraParams camera;
  camera.size = 8;
  camera.projection = projection;
  return {render_volume(scene, camera, params), vertex_ambient_occlusion(scene, params)};
}

void expect_same(const std::vector<float>& a, const std::vector<float>& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::isnan(b[i]))
      ASSERT_TRUE(std::isnan(a[i])) << what << ' ' << i;
    else
      ASSERT_EQ(a[i], b[i]) << what << ' ' << i;
  }
}

// Every file of one run, read back and checked against the library's result.
void expect_outputs(const std::string& prefix, const Expected& expected) {
  for (const char* suffix : kSuffixes) ASSERT_TRUE(std::filesystem::is_regular_file(prefix + suffix)) << prefix << suffix;
  const Volume& v = expected.volume;

  const test::VtiFile vti = test::read_vti(prefix + ".vti");
  test::expect_vti_grid(vti, 7, v);
  ASSERT_EQ(vti.arrays.count("ao"), 1u);
  ASSERT_EQ(vti.arrays.count("depth"), 1u);
  expect_same(vti.arrays.at("ao"), v.ao, "vti ao");
  expect_same(vti.arrays.at("depth"), v.depth, "vti depth");

  for (const auto& [suffix, values] : {std::pair{".ao.nrrd", &v.ao}, std::pair{".depth.nrrd", &v.depth}}) {
    const test::NrrdFile nrrd = test::read_nrrd(prefix + suffix);
    EXPECT_EQ(nrrd.magic, "NRRD0004") << suffix;
    ASSERT_EQ(nrrd.fields.count("sizes"), 1u) << suffix;
    EXPECT_EQ(nrrd.fields.at("sizes"), "8 8 8") << suffix;
    EXPECT_EQ(nrrd.fields.at("type"), "float") << suffix;
    expect_same(nrrd.data, *values, suffix);
  }

  test::expect_montage_shows(test::read_image(prefix + ".png"), v.dims, v.ao);

  // The mesh: every 'v' line has x y z w and the vertex's AO, which reads back as the library's.
  std::ifstream mesh_file(prefix + ".tet4");
  std::size_t v_lines = 0;
  for (std::string line; std::getline(mesh_file, line);)
    if (line.rfind("v ", 0) == 0) {
      ++v_lines;
      EXPECT_EQ(test::numbers(line.substr(2)).size(), 5u) << line;
    }
  std::vector<double> values;
  const TetMesh mesh = read_mesh(prefix + ".tet4", &values);
  const TetMesh shape = make_shape("two-tetrahedra", 10);
  EXPECT_EQ(v_lines, shape.vertices.size());
  EXPECT_EQ(mesh.vertices, shape.vertices);
  EXPECT_EQ(mesh.cells, shape.cells);
  EXPECT_EQ(values, expected.vertex_ao);
}

TEST(Cli, VolumeModeWritesEveryFileAsTheLibraryComputesIt) {
  const std::string prefix = fresh_prefix("cli_volume");
  const Result r = run(std::string(kVolumeArgs) + " -o " + prefix);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output, "");  // -q: no progress, no summary
  const Expected expected = library_result(Projection::orthographic, false, 1);
  expect_outputs(prefix, expected);
  // The scene is worth rendering: the floor and both pyramids are seen, some of it occluded, and
  // the border voxels (beyond the floor's [-2, 2]^3) miss.
  int hits = 0, occluded = 0;
  for (float ao : expected.volume.ao)
    if (!std::isnan(ao)) {
      ++hits;
      occluded += ao > 0;
      EXPECT_LE(ao, 1.0f);
    }
  EXPECT_GT(hits, 100);
  EXPECT_LT(hits, 512);
  EXPECT_GT(occluded, 10);
  // The pyramids' 8 base vertices rest on the floor, which occludes them; nothing else is near
  // the floor's corners or above the apexes.
  int vertices_occluded = 0;
  for (double ao : expected.vertex_ao) vertices_occluded += ao > 0;
  EXPECT_EQ(vertices_occluded, 8);
}

std::string file_bytes(const std::string& file) {
  return test::slurp(file);
}

TEST(Cli, SameSeedGivesIdenticalFilesForAnyThreadCountAndAnotherSeedDiffers) {
  const std::string a = fresh_prefix("cli_seed_a"), b = fresh_prefix("cli_seed_b"), c = fresh_prefix("cli_seed_c");
  ASSERT_EQ(run(std::string(kVolumeArgs) + " --seed 5 --threads 1 -o " + a).status, 0);
  ASSERT_EQ(run(std::string(kVolumeArgs) + " --seed 5 --threads 3 -o " + b).status, 0);
  ASSERT_EQ(run(std::string(kVolumeArgs) + " --seed 6 -o " + c).status, 0);
  for (const char* suffix : kSuffixes) {
    ASSERT_TRUE(std::filesystem::is_regular_file(a + suffix)) << suffix;
    EXPECT_EQ(file_bytes(a + suffix), file_bytes(b + suffix)) << suffix;
  }
  expect_outputs(a, library_result(Projection::orthographic, false, 5));
  // Another seed draws other directions: the AO differs, the geometry (depth) does not.
  EXPECT_NE(file_bytes(a + ".ao.nrrd"), file_bytes(c + ".ao.nrrd"));
  EXPECT_NE(file_bytes(a + ".tet4"), file_bytes(c + ".tet4"));
  EXPECT_EQ(file_bytes(a + ".depth.nrrd"), file_bytes(c + ".depth.nrrd"));
  expect_outputs(c, library_result(Projection::orthographic, false, 6));
}

TEST(Cli, CosineAndPerspectiveReachTheRenderer) {
  const std::string plain = fresh_prefix("cli_plain"), cosine = fresh_prefix("cli_cosine"),
                    perspective = fresh_prefix("cli_perspective");
  ASSERT_EQ(run(std::string(kVolumeArgs) + " -o " + plain).status, 0);
  ASSERT_EQ(run(std::string(kVolumeArgs) + " --cosine -o " + cosine).status, 0);
  ASSERT_EQ(run(std::string(kVolumeArgs) + " --perspective -o " + perspective).status, 0);
  expect_outputs(cosine, library_result(Projection::orthographic, true, 1));
  expect_outputs(perspective, library_result(Projection::perspective, false, 1));
  // Cosine weighting changes the AO but not what the camera sees.
  EXPECT_NE(file_bytes(plain + ".ao.nrrd"), file_bytes(cosine + ".ao.nrrd"));
  EXPECT_EQ(file_bytes(plain + ".depth.nrrd"), file_bytes(cosine + ".depth.nrrd"));
  // Perspective rays diverge from the eye: tilted ones travel farther than the orthographic ray
  // from the same screen point (most voxels see the floor, 1.35 beyond the screen either way).
  const auto ortho_depth = test::read_vti(plain + ".vti").arrays.at("depth");
  const auto persp_depth = test::read_vti(perspective + ".vti").arrays.at("depth");
  ASSERT_EQ(ortho_depth.size(), persp_depth.size());
  int longer = 0;
  for (std::size_t i = 0; i < ortho_depth.size(); ++i)
    longer += !std::isnan(ortho_depth[i]) && !std::isnan(persp_depth[i]) && persp_depth[i] > ortho_depth[i] * 1.0001f;
  EXPECT_GT(longer, 100);
}

}  // namespace
