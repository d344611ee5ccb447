// The camera and the volume files, read back with the small readers of volume_files.hpp, which are
// independent of the writers.
#include "ao4d/render.hpp"
#include "ao4d/shapes.hpp"
#include "helpers.hpp"
#include "volume_files.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

namespace ao4d {
namespace {

using test::read_vti;
using test::VtiFile;

void expect_same(const std::vector<float>& a, const std::vector<float>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (std::isnan(b[i]))
      ASSERT_TRUE(std::isnan(a[i])) << i;
    else
      ASSERT_EQ(a[i], b[i]) << i;
  }
}

TEST(Volume, OrthographicDepthOfAHypersphereAndItsVtiReadBack) {
  const Scene scene(make_shape("hypersphere", 8));
  CameraParams camera;
  camera.size = 9;  // odd, so the centre voxel looks at x = y = z = 0
  AoParams params;
  params.rays = 32;
  params.radius = 0.5;
  const Volume volume = render_volume(scene, camera, params);
  ASSERT_EQ(volume.ao.size(), 729u);

  // The camera's screen is at w = min_w - 0.05 * diagonal; the centre ray meets the sphere at
  // w = -1 (within the chord sag of the marched surface), a corner ray misses it.
  const double screen = scene.bounds_min().w - 0.05 * scene.diagonal();
  const std::size_t centre = 4 + 9 * (4 + 9 * 4);
  EXPECT_NEAR(volume.depth[centre], -1.0 - screen, 0.02);
  EXPECT_TRUE(std::isnan(volume.depth[0]));
  EXPECT_TRUE(std::isnan(volume.ao[0]));
  // On a convex surface nothing occludes. The marched surface is only nearly convex (linear
  // interpolation leaves shallow creases between cells), so AO is small rather than 0.
  int seen = 0;
  double sum = 0;
  for (float ao : volume.ao)
    if (!std::isnan(ao)) {
      ++seen;
      sum += ao;
    }
  EXPECT_GT(seen, 100);
  EXPECT_LT(sum / seen, 0.05);

  const auto file = std::filesystem::path(AO4D_TEST_OUTPUT_DIR) / "hypersphere.vti";
  write_vti(file, volume);
  const VtiFile vti = read_vti(file);
  expect_vti_grid(vti, 8, volume);
  ASSERT_EQ(vti.arrays.size(), 2u);
  expect_same(vti.arrays.at("ao"), volume.ao);
  expect_same(vti.arrays.at("depth"), volume.depth);
}

// The perspective eye sits eye_distance scene diagonals in front of the screen (w = min_w - 0.05
// diagonal), on the image's axis. Against the floor w = 0 every voxel's ray is known in closed form:
// the centre ray goes straight along w, and any ray through screen point o reaches w = 0 after
// (0.05 diagonal) / cos, cos = eye_distance diagonal / |o - eye|, at o's x, y, z scaled by
// 1 + 0.05 / eye_distance: it hits where that lies inside the floor's [-1, 1]^3, and misses elsewhere.
TEST(Volume, PerspectiveDepthFollowsTheRaysFromTheEye) {
  const Scene scene(test::floor_mesh(1.0));
  const double diagonal = std::sqrt(12.0);
  ASSERT_NEAR(scene.diagonal(), diagonal, 1e-12);
  const double screen = -0.05 * diagonal;
  for (const double eye_distance : {1.5, 0.5}) {
    CameraParams camera;
    camera.size = 5;  // odd, so the centre voxel looks along the axis; voxels at 0, +-0.525, +-1.05
    camera.projection = Projection::perspective;
    camera.eye_distance = eye_distance;
    AoParams params;
    params.rays = 8;
    const Volume volume = render_volume(scene, camera, params);
    const Vec4 eye{0, 0, 0, screen - eye_distance * diagonal};
    const std::size_t centre = 2 + 5 * (2 + 5 * 2);
    EXPECT_NEAR(volume.depth[centre], 0.05 * diagonal, 1e-6);  // the gap between screen and floor
    int hits = 0, misses = 0;
    for (int k = 0; k < 5; ++k)
      for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) {
          const std::size_t voxel = static_cast<std::size_t>(i + 5 * (j + 5 * k));
          const Vec4 o{volume.origin[0] + i * volume.spacing[0], volume.origin[1] + j * volume.spacing[1],
                       volume.origin[2] + k * volume.spacing[2], screen};
          const double cos = eye_distance * diagonal / length(o - eye);
          const Vec4 on_floor = o * (1 + 0.05 / eye_distance);
          const bool inside = std::abs(on_floor.x) < 1 && std::abs(on_floor.y) < 1 && std::abs(on_floor.z) < 1;
          if (inside) {
            ++hits;
            EXPECT_NEAR(volume.depth[voxel], 0.05 * diagonal / cos, 1e-6) << i << ' ' << j << ' ' << k;
            EXPECT_EQ(volume.ao[voxel], 0.0f) << i << ' ' << j << ' ' << k;  // nothing above a lone plane
          } else {
            ++misses;
            EXPECT_TRUE(std::isnan(volume.depth[voxel])) << i << ' ' << j << ' ' << k;
            EXPECT_TRUE(std::isnan(volume.ao[voxel])) << i << ' ' << j << ' ' << k;
          }
        }
    // Off the axis the rays are longer than the centre one, by the factor 1 / cos.
    const std::size_t off_axis = 3 + 5 * (3 + 5 * 3);
    EXPECT_GT(volume.depth[off_axis], volume.depth[centre] * 1.0001f);
    EXPECT_EQ(hits, 27);  // the inner 3^3 voxels; the outer layer lands beyond |x| = 1
    EXPECT_EQ(misses, 125 - 27);
  }
}

TEST(Volume, NrrdHeaderAndDataReadBack) {
  const Scene scene(make_shape("hypersphere", 6));
  CameraParams camera;
  camera.size = 4;
  AoParams params;
  params.rays = 8;
  const Volume volume = render_volume(scene, camera, params);
  const auto file = std::filesystem::path(AO4D_TEST_OUTPUT_DIR) / "hypersphere.depth.nrrd";
  write_nrrd(file, volume, volume.depth);
  const test::NrrdFile nrrd = test::read_nrrd(file);
  EXPECT_EQ(nrrd.magic, "NRRD0004");
  EXPECT_EQ(nrrd.fields.at("type"), "float");
  EXPECT_EQ(nrrd.fields.at("dimension"), "3");
  EXPECT_EQ(nrrd.fields.at("space dimension"), "3");
  EXPECT_EQ(nrrd.fields.at("sizes"), "4 4 4");
  EXPECT_EQ(nrrd.fields.at("endian"), "little");
  EXPECT_EQ(nrrd.fields.at("encoding"), "raw");
  // One vector per axis, (x,y,z): axis a steps spacing[a] along a only; the origin is voxel 0's.
  const auto directions = test::numbers(nrrd.fields.at("space directions"), "(),");
  ASSERT_EQ(directions.size(), 9u) << nrrd.fields.at("space directions");
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t b = 0; b < 3; ++b)
      EXPECT_NEAR(directions[3 * a + b], a == b ? volume.spacing[a] : 0.0, 1e-8) << a << ' ' << b;
  const auto origin = test::numbers(nrrd.fields.at("space origin"), "(),");
  ASSERT_EQ(origin.size(), 3u) << nrrd.fields.at("space origin");
  for (std::size_t a = 0; a < 3; ++a) EXPECT_NEAR(origin[a], volume.origin[a], 1e-8) << a;
  EXPECT_GT(volume.spacing[0], 0.5);  // the hypersphere's bounds over 4 voxels: not a unit default
  expect_same(nrrd.data, volume.depth);
}

// The montage's layout: slices in rows of ceil(sqrt(nz)) from the top left, 2 pixels of grey (96)
// around each, y up within a slice; brightness 255 (1 - AO), misses dark blue (16, 24, 64).
TEST(Volume, MontagePlacesEverySliceAndShadesByAo) {
  Volume volume;
  volume.dims = {4, 3, 5};  // 3 columns of slices, 2 rows: 3 * (4 + 2) + 2 by 2 * (3 + 2) + 2
  volume.spacing = {1, 1, 1};
  volume.ao.assign(60, std::numeric_limits<float>::quiet_NaN());
  volume.depth = volume.ao;
  const auto at = [&](int i, int j, int k) -> float& { return volume.ao[static_cast<std::size_t>(i + 4 * (j + 3 * k))]; };
  at(1, 0, 4) = 0.25f;  // slice 4: second row, second column; j = 0 is the slice's bottom row
  at(0, 2, 0) = 0.0f;   // slice 0, top left
  at(3, 1, 2) = 1.0f;   // slice 2: first row, third column
  const auto file = std::filesystem::path(AO4D_TEST_OUTPUT_DIR) / "layout.png";
  std::filesystem::remove(file);
  write_montage(file, volume);
  const test::Image png = test::read_image(file);
  ASSERT_EQ(png.width, 20);
  ASSERT_EQ(png.height, 12);
  ASSERT_EQ(png.channels, 3);
  using Rgb = std::array<int, 3>;
  const Rgb grey{96, 96, 96}, blue{16, 24, 64};
  EXPECT_EQ(png.rgb(2 + 6 + 1, 2 + 5 + 2), (Rgb{191, 191, 191}));  // lround(255 * 0.75)
  EXPECT_EQ(png.rgb(2, 2), (Rgb{255, 255, 255}));
  EXPECT_EQ(png.rgb(2 + 12 + 3, 2 + 1), (Rgb{0, 0, 0}));
  EXPECT_EQ(png.rgb(2, 2 + 2), blue);               // voxel (0, 0, 0), a miss
  EXPECT_EQ(png.rgb(0, 0), grey);                   // the border
  EXPECT_EQ(png.rgb(2 + 4, 2), grey);               // between slices 0 and 1
  EXPECT_EQ(png.rgb(2 + 12 + 1, 2 + 5 + 1), grey);  // where a sixth slice would go
  int blues = 0;
  for (int y = 0; y < png.height; ++y)
    for (int x = 0; x < png.width; ++x) blues += png.rgb(x, y) == blue;
  EXPECT_EQ(blues, 60 - 3);
}

TEST(Volume, MontageOfARenderedFloor) {
  const Scene scene(test::floor_mesh(1.0));
  CameraParams camera;
  camera.size = 5;
  AoParams params;
  params.rays = 4;
  const auto file = std::filesystem::path(AO4D_TEST_OUTPUT_DIR) / "floor.png";
  std::filesystem::remove(file);
  const Volume volume = render_volume(scene, camera, params);
  write_montage(file, volume);
  const test::Image png = test::read_image(file);
  // 5 slices: 3 columns, 2 rows of 5 x 5 voxels.
  ASSERT_EQ(png.width, 3 * (5 + 2) + 2);
  ASSERT_EQ(png.height, 2 * (5 + 2) + 2);
  ASSERT_EQ(png.channels, 3);
  using Rgb = std::array<int, 3>;
  // Orthographic rays at x, y, z in {0, +-0.525} hit the lone plane (AO 0, white), those at
  // +-1.05 pass beside it (dark blue). Slice k = 2 is the first row's third column.
  const int x0 = 2 + 2 * 7, y0 = 2;
  EXPECT_EQ(png.rgb(x0 + 2, y0 + 2), (Rgb{255, 255, 255}));
  EXPECT_EQ(png.rgb(x0 + 1, y0 + 3), (Rgb{255, 255, 255}));
  EXPECT_EQ(png.rgb(x0, y0 + 2), (Rgb{16, 24, 64}));
  EXPECT_EQ(png.rgb(x0 + 2, y0), (Rgb{16, 24, 64}));
  EXPECT_EQ(png.rgb(2 + 2, 2 + 2), (Rgb{16, 24, 64}));      // slice 0 lies at z = -1.05: all misses
  test::expect_montage_shows(png, volume.dims, volume.ao);  // and every other pixel as laid out
}

// Voxel i is seeded by its index alone, so the thread that renders it does not matter.
TEST(Volume, DoesNotDependOnTheThreadCount) {
  const Scene scene(make_shape("torus", 6));
  CameraParams camera;
  camera.size = 10;
  AoParams params;
  params.radius = 0.5;
  params.rays = 16;
  params.threads = 1;
  const Volume one = render_volume(scene, camera, params);
  int occluded = 0;
  for (float ao : one.ao) occluded += !std::isnan(ao) && ao > 0;
  EXPECT_GT(occluded, 20);  // enough voxels whose value depends on their random directions
  params.threads = 3;
  const Volume three = render_volume(scene, camera, params);
  expect_same(three.ao, one.ao);
  expect_same(three.depth, one.depth);
  params.seed = 2;
  const Volume other = render_volume(scene, camera, params);
  expect_same(other.depth, one.depth);  // the geometry does not depend on the seed
  int changed = 0;
  for (std::size_t i = 0; i < one.ao.size(); ++i) changed += !std::isnan(one.ao[i]) && other.ao[i] != one.ao[i];
  EXPECT_GT(changed, 0);
}

}  // namespace
}  // namespace ao4d
