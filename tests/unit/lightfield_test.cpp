// The light field display models: the three spaces of HoloVizio-style displays, the quilt's views and
// the lenticular interleave, and the display files.
#include "lightfield/display_file.h"
#include "lightfield/modules.h"
#include "lightfield/quilt.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>

namespace {

using lightfield::Box;
using lightfield::Module;

lightfield::ModulesDisplay c80() {
  lightfield::Display display;
  std::string error;
  EXPECT_TRUE(lightfield::load_display(PLAYER_BOARD_DIR "/displays/holovizio-c80.toml", display, error)) << error;
  return display.modules;
}

TEST(LightfieldRoi, MapsTheWorldBoxUniformlyIntoThePhysicalBoxCentred) {
  const Box world{{-2, 0, 10}, {2, 1, 12}}, physical{{-0.8, -0.45, -0.3}, {0.8, 0.45, 0.3}};
  const auto t = lightfield::roi_transform(world, physical);
  ASSERT_TRUE(t);
  EXPECT_DOUBLE_EQ(t->scale, 0.3);  // the tightest axis: z, 0.6 / 2 (x gives 0.4, y 0.9)
  const glm::dvec3 centre = t->to_physical({0, 0.5, 11});
  EXPECT_NEAR(glm::length(centre), 0.0, 1e-12);
  EXPECT_NEAR(t->to_physical({0, 0, 12}).z, 0.3, 1e-12);
  EXPECT_NEAR(t->to_physical({2, 0, 12}).x, 0.6, 1e-12);  // inside the box: x is not the tight axis
  const glm::dvec3 p(1.25, -3.5, 7.0);
  EXPECT_NEAR(glm::length(t->to_world(t->to_physical(p)) - p), 0.0, 1e-12);
  const glm::dvec4 by_matrix = t->world_to_physical() * glm::dvec4(p, 1.0);
  EXPECT_NEAR(glm::length(glm::dvec3(by_matrix) - t->to_physical(p)), 0.0, 1e-12);
  const glm::dvec4 back = t->physical_to_world() * by_matrix;
  EXPECT_NEAR(glm::length(glm::dvec3(back) - p), 0.0, 1e-12);
  // The two matrices are each other's inverse as 4x4 matrices, w row included: the shaders take
  // them as they are.
  const glm::dmat4 round_trip = t->physical_to_world() * t->world_to_physical();
  for (int column = 0; column < 4; ++column)
    for (int row = 0; row < 4; ++row) EXPECT_NEAR(round_trip[column][row], column == row ? 1.0 : 0.0, 1e-12) << column << row;
  EXPECT_FALSE(lightfield::roi_transform(Box{{0, 0, 0}, {1, 0, 1}}, physical));  // flat world box
}

// A transform nobody computed maps each space onto itself, whichever way it is asked.
TEST(LightfieldRoi, ADefaultTransformIsTheIdentity) {
  const lightfield::RoiTransform identity;
  const glm::dvec3 p(1.25, -3.5, 7.0);
  EXPECT_EQ(identity.to_physical(p), p);
  EXPECT_EQ(identity.to_world(p), p);
  EXPECT_EQ(identity.world_to_physical(), glm::dmat4(1.0));
  EXPECT_EQ(identity.physical_to_world(), glm::dmat4(1.0));
  // Likewise a quilt view nobody computed: the camera at the origin, projecting as it stands.
  const lightfield::OffAxisView view;
  EXPECT_EQ(view.view, glm::dmat4(1.0));
  EXPECT_EQ(view.projection, glm::dmat4(1.0));
  EXPECT_EQ(view.eye, glm::dvec3(0.0));
}

// A scene flat along an axis (a single quad, a line, a point) still maps to a box: a thousandth of
// its largest side along each flat axis, centred on it, and nothing added along the others.
TEST(LightfieldRoi, AFlatSceneGetsAThinBoxAlongItsFlatAxesOnly) {
  lightfield::ModulesDisplay display;
  const Box quad{{-2.0, 0.0, 5.0}, {2.0, 1.0, 5.0}};
  const Box quad_box = lightfield::world_roi(display, quad);
  EXPECT_EQ(quad_box.min, glm::dvec3(-2.0, 0.0, 5.0 - 0.002));
  EXPECT_EQ(quad_box.max, glm::dvec3(2.0, 1.0, 5.0 + 0.002));
  const Box line{{0.0, -1.0, 0.0}, {0.0, 3.0, 0.0}};
  const Box line_box = lightfield::world_roi(display, line);
  EXPECT_EQ(line_box.min, glm::dvec3(-0.002, -1.0, -0.002));
  EXPECT_EQ(line_box.max, glm::dvec3(0.002, 3.0, 0.002));
  // A point: no side to take a thousandth of; a micrometre's thousandth then, still a box.
  const Box point_box = lightfield::world_roi(display, Box{{1.0, 2.0, 3.0}, {1.0, 2.0, 3.0}});
  EXPECT_EQ(point_box.min, glm::dvec3(1.0, 2.0, 3.0) - 0.5e-9);
  EXPECT_EQ(point_box.max, glm::dvec3(1.0, 2.0, 3.0) + 0.5e-9);
  EXPECT_TRUE(lightfield::roi_transform(point_box, Box{{-1, -1, -1}, {1, 1, 1}}));
  // A region the display file gives is used as it is, flat or not.
  display.world_roi = Box{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}};
  EXPECT_EQ(lightfield::world_roi(display, quad).max, glm::dvec3(1.0));
}

TEST(LightfieldModules, PhysicalToImageOfKnownPoints) {
  const lightfield::ModulesDisplay display = c80();
  ASSERT_EQ(display.module_x.size(), 80u);
  const Module m = lightfield::module_of(display, 0);
  EXPECT_DOUBLE_EQ(m.x, -1.0);
  EXPECT_DOUBLE_EQ(m.z, -1.2);
  // A point on the screen is shown where it is, by every module.
  const auto on_screen = lightfield::physical_to_image(m, {0.4, 0.225, 0.0});
  ASSERT_TRUE(on_screen);
  EXPECT_NEAR(on_screen->x, 1.2 / 1.6 * 320, 1e-9);
  EXPECT_NEAR(on_screen->y, 0.225 / 0.9 * 180, 1e-9);
  // In front of the screen, by hand: S.x = -1 + 1.2 * 1.2 / 1.7, S.y = 0.1 + 0.2 * 2.5 / 2.0 = 0.35,
  // u = (S.x + 0.8) / 1.6 * 320, v = (0.45 - 0.35) / 0.9 * 180 = 20.
  const auto front = lightfield::physical_to_image(m, {0.2, 0.3, 0.5});
  ASSERT_TRUE(front);
  EXPECT_NEAR(front->x, (-1.0 + 1.44 / 1.7 + 0.8) / 1.6 * 320, 1e-9);
  EXPECT_NEAR(front->y, 20.0, 1e-9);
  EXPECT_DOUBLE_EQ(front->z, 0.5);
  // Behind the module or beyond the observer line nothing is shown.
  EXPECT_FALSE(lightfield::physical_to_image(m, {0, 0, -1.3}));
  EXPECT_FALSE(lightfield::physical_to_image(m, {0, 0, 2.5}));
}

TEST(LightfieldModules, EachPixelsRayPassesThroughThePointItShows) {
  const lightfield::ModulesDisplay display = c80();
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k : {0, 17, 40, 79}) {
    const Module m = lightfield::module_of(display, k);
    for (int trial = 0; trial < 200; ++trial) {
      const double u = unit(random) * m.width, v = unit(random) * m.height;
      const glm::dvec3 s = lightfield::screen_point_of_pixel(m, u, v);
      const glm::dvec3 o = lightfield::observer_point(m, s);
      EXPECT_DOUBLE_EQ(o.z, display.observer_distance);
      // The observer point, S and the module are on one line seen from above (horizontal parallax).
      const glm::dvec2 to_s(s.x - m.x, s.z - m.z), to_o(o.x - m.x, o.z - m.z);
      EXPECT_NEAR(to_s.x * to_o.y - to_s.y * to_o.x, 0.0, 1e-9);
      // On the module's plane and on the observer line the mapping is not defined: no image.
      EXPECT_FALSE(lightfield::physical_to_image(m, {s.x, s.y, m.z}));
      EXPECT_FALSE(lightfield::physical_to_image(m, o));
      for (double t : {0.1, 0.4, 0.7, 1.3, 1.6}) {  // points between S and O, and behind the screen
        const glm::dvec3 q = o + t * (s - o);
        if (q.z <= m.z + 1e-6) continue;
        const auto image = lightfield::physical_to_image(m, q);
        ASSERT_TRUE(image);
        EXPECT_NEAR(image->x, u, 1e-7) << "module " << k << " t " << t;
        EXPECT_NEAR(image->y, v, 1e-7) << "module " << k << " t " << t;
      }
    }
  }
}

TEST(LightfieldModules, ClipPositionPutsEachVertexOnItsExactPixelAndOrdersDepthTowardsTheObserver) {
  const lightfield::ModulesDisplay display = c80();
  const Module m = lightfield::module_of(display, 23);
  EXPECT_GT(m.z_front, display.physical_roi.max.z);
  EXPECT_LT(m.z_back, display.physical_roi.min.z);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> x(-0.8, 0.8), y(-0.45, 0.45), z(-0.3, 0.3);
  for (int trial = 0; trial < 500; ++trial) {
    const glm::dvec3 q(x(random), y(random), z(random));
    const glm::dvec4 clip = lightfield::clip_position(m, q);
    const auto image = lightfield::physical_to_image(m, q);
    ASSERT_TRUE(image);
    ASSERT_GT(clip.w, 0.0);
    EXPECT_NEAR((clip.x / clip.w * 0.5 + 0.5) * m.width, image->x, 1e-9);
    EXPECT_NEAR((0.5 - clip.y / clip.w * 0.5) * m.height, image->y, 1e-9);
    const glm::dvec3 nearer = q + glm::dvec3(0, 0, 0.01);
    const glm::dvec4 clip_nearer = lightfield::clip_position(m, nearer);
    EXPECT_LT(clip_nearer.z / clip_nearer.w, clip.z / clip.w);  // nearer the observer: in front
    EXPECT_GT(clip.z / clip.w, -1.0);
    EXPECT_LT(clip.z / clip.w, 1.0);
  }
}

// A region as deep as the whole space between the modules and the observers: the depth range is
// cut 2% of that distance short of either end, where the mapping is still finite, and every
// point of the region between those ends lands inside the depth range with a finite image.
TEST(LightfieldModules, ADeepRegionsDepthRangeStopsShortOfTheModulesAndTheObservers) {
  lightfield::ModulesDisplay display = c80();
  display.physical_roi.min.z = display.module_z + 1e-3;
  display.physical_roi.max.z = display.observer_distance - 1e-3;
  const Module m = lightfield::module_of(display, 40);
  const double margin = 0.02 * (display.observer_distance - display.module_z);
  EXPECT_DOUBLE_EQ(m.z_back, display.module_z + margin);
  EXPECT_DOUBLE_EQ(m.z_front, display.observer_distance - margin);
  for (const double z : {m.z_back, m.z_front}) {
    const glm::dvec4 clip = lightfield::clip_position(m, {0.1, 0.2, z});
    ASSERT_GT(clip.w, 0.0);
    EXPECT_TRUE(std::isfinite(clip.x / clip.w) && std::isfinite(clip.y / clip.w));
    EXPECT_NEAR(std::abs(clip.z / clip.w), 1.0, 1e-9);
    EXPECT_TRUE(lightfield::physical_to_image(m, {0.1, 0.2, z}));
  }
}

TEST(LightfieldModules, EdgesBendOnlyWhereDepthChanges) {
  const Module m = lightfield::module_of(c80(), 5);
  // At one depth both perspectives are affine: a straight edge stays straight and exact.
  EXPECT_LT(lightfield::edge_error_pixels(m, {-0.5, -0.3, 0.1}, {0.6, 0.4, 0.1}), 1e-9);
  // Along depth the vertical perspective is not the rasteriser's: the error is real and measured.
  const double deep = lightfield::edge_error_pixels(m, {0.0, 0.4, -0.3}, {0.0, 0.4, 0.3});
  EXPECT_GT(deep, 0.5);
  // At the observer line's height the vertical perspective has nothing to move, and horizontally the
  // rasteriser's perspective is the module's own: no error even across depth.
  EXPECT_LT(lightfield::edge_error_pixels(m, {-0.6, m.observer_height, -0.3}, {0.6, m.observer_height, 0.3}), 1e-9);
}

// An edge that runs behind the module (z below -1.2) or past the observer (z above 2.5) is measured
// only where the module shows its points: the rest has nothing to compare with, and must neither
// add to the error nor stop the measurement. At the observer's height the error of the part shown
// is zero, so any contribution of the parts not shown would show.
TEST(LightfieldModules, AnEdgeLeavingTheModulesDepthRangeIsMeasuredWhereTheModuleShowsIt) {
  const Module m = lightfield::module_of(c80(), 5);
  const double height = m.observer_height;
  EXPECT_LT(lightfield::edge_error_pixels(m, {-0.6, height, 0.3}, {0.6, height, 4.0}), 1e-9);
  EXPECT_LT(lightfield::edge_error_pixels(m, {-0.6, height, -3.0}, {0.6, height, 0.3}), 1e-9);
  EXPECT_LT(lightfield::edge_error_pixels(m, {-0.6, height, -3.0}, {0.6, height, 4.0}), 1e-9);
  // Off that height the part shown has a real error, and it stays finite.
  const double partly_shown = lightfield::edge_error_pixels(m, {0.0, 0.4, 0.0}, {0.0, 0.4, 4.0});
  EXPECT_GT(partly_shown, 0.5);
  EXPECT_TRUE(std::isfinite(partly_shown));
}

TEST(LightfieldModules, SeesExactlyTheModulesWhoseImageTheBoxReaches) {
  lightfield::ModulesDisplay display = c80();
  display.footprint = {0.6, 0.8};  // each module fills only the right part of the screen
  const Box small{{0.3, -0.1, -0.1}, {0.5, 0.1, 0.1}};
  int seen = 0;
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int k = 0; k < 80; ++k) {
    const Module m = lightfield::module_of(display, k);
    const bool sees = lightfield::sees(m, small);
    seen += sees ? 1 : 0;
    // Brute force: whether any of many points of the box lands in the image.
    bool hit = false;
    for (int trial = 0; trial < 4000 && !hit; ++trial) {
      const glm::dvec3 q = small.min + (small.max - small.min) * glm::dvec3(unit(random), unit(random), unit(random));
      const auto image = lightfield::physical_to_image(m, q);
      hit = image && image->x >= 0 && image->x <= m.width && image->y >= 0 && image->y <= m.height;
    }
    if (hit) {
      EXPECT_TRUE(sees) << "module " << k;
    }
  }
  EXPECT_GT(seen, 0);
  EXPECT_LT(seen, 80);
  // By hand: the module at x = -1 shows the box between S.x = 0.2 and 0.636 (reaching the footprint);
  // the one at x = 1 between 0.236 and 0.538 (short of it).
  EXPECT_TRUE(lightfield::sees(lightfield::module_of(display, 0), small));
  EXPECT_FALSE(lightfield::sees(lightfield::module_of(display, 79), small));
}

TEST(LightfieldModules, MontageGridIsAsSquareAsItGets) {
  EXPECT_EQ(lightfield::montage_grid(1), glm::ivec2(1, 1));
  EXPECT_EQ(lightfield::montage_grid(8), glm::ivec2(3, 3));
  EXPECT_EQ(lightfield::montage_grid(80), glm::ivec2(9, 9));
  EXPECT_EQ(lightfield::montage_grid(32), glm::ivec2(6, 6));
}

// pitch 50, slope -5, center 0.1, DPI 300, a 100x50 panel, 10 views: p = 50 * 100 / 300 * cos(atan(-1/5))
// = 16.3430, t = 50 / (100 * -5) = -0.1, s = 1/300. Pixel (0, 0), red: u = 0.005, v = 0.01,
// (0.005 - 0.001) * 16.343 - 0.1 = -0.0346, fract 0.9654: view 9; green: (0.005 + 1/300 - 0.001) *
// 16.343 - 0.1 = 0.0198: view 0. The others likewise (computed with the formula in double precision,
// none within 0.04 views of a boundary).
TEST(LightfieldQuilt, InterleaveAssignsHandComputedViews) {
  lightfield::Calibration c;
  c.pitch = 50;
  c.slope = -5;
  c.center = 0.1;
  c.dpi = 300;
  c.screen_width = 100;
  c.screen_height = 50;
  struct Case {
    int x, y;
    int views[3], inverted[3], flipped[3];
  };
  const Case cases[] = {{0, 0, {9, 0, 0}, {0, 9, 9}, {9, 0, 1}},
                        {37, 5, {8, 9, 9}, {1, 0, 0}, {2, 2, 3}},
                        {99, 49, {5, 5, 6}, {4, 4, 3}, {7, 8, 8}},
                        {50, 25, {3, 3, 4}, {6, 6, 5}, {9, 0, 0}}};
  for (const Case& test : cases)
    for (int channel = 0; channel < 3; ++channel) {
      c.inverted_views = false;
      c.flip_x = false;
      EXPECT_EQ(lightfield::view_of_subpixel(lightfield::interleave_of(c, 10), c, test.x, test.y, channel), test.views[channel])
          << test.x << "," << test.y << " channel " << channel;
      c.inverted_views = true;
      EXPECT_EQ(lightfield::view_of_subpixel(lightfield::interleave_of(c, 10), c, test.x, test.y, channel),
                test.inverted[channel])
          << "invView " << test.x << "," << test.y << " channel " << channel;
      c.inverted_views = false;
      c.flip_x = true;
      EXPECT_EQ(lightfield::view_of_subpixel(lightfield::interleave_of(c, 10), c, test.x, test.y, channel), test.flipped[channel])
          << "flipImageX " << test.x << "," << test.y << " channel " << channel;
    }
}

TEST(LightfieldQuilt, TilesRunFromTheBottomLeftAlongRows) {
  lightfield::QuiltDisplay quilt;
  quilt.columns = 5;
  quilt.rows = 9;
  EXPECT_EQ(quilt.views(), 45);
  EXPECT_EQ(lightfield::tile_of(quilt, 0), glm::ivec2(0, 0));
  EXPECT_EQ(lightfield::tile_of(quilt, 4), glm::ivec2(4, 0));
  EXPECT_EQ(lightfield::tile_of(quilt, 5), glm::ivec2(0, 1));
  EXPECT_EQ(lightfield::tile_of(quilt, 44), glm::ivec2(4, 8));
}

TEST(LightfieldQuilt, ViewsShareTheFocalPlaneWindowAndShowParallaxAroundIt) {
  const glm::dvec3 eye(0, 1, 5), target(0, 1, 0), up(0, 1, 0);
  const double fov = glm::radians(30.0), aspect = 420.0 / 560.0;
  const auto ndc = [](const lightfield::OffAxisView& v, const glm::dvec3& p) {
    const glm::dvec4 clip = v.projection * v.view * glm::dvec4(p, 1.0);
    return glm::dvec3(clip) / clip.w;
  };
  const lightfield::OffAxisView centre = lightfield::quilt_view(eye, target, up, fov, aspect, 0.1, 50, 40, 22, 45);
  const lightfield::OffAxisView first = lightfield::quilt_view(eye, target, up, fov, aspect, 0.1, 50, 40, 0, 45);
  const lightfield::OffAxisView last = lightfield::quilt_view(eye, target, up, fov, aspect, 0.1, 50, 40, 44, 45);
  // View 0 sits at -20 degrees seen from the target, view 44 at +20.
  EXPECT_NEAR(first.eye.x, -5 * std::tan(glm::radians(20.0)), 1e-9);
  EXPECT_NEAR(last.eye.x, 5 * std::tan(glm::radians(20.0)), 1e-9);
  EXPECT_NEAR(centre.eye.x, 0.0, 1e-9);
  // Every point of the focal plane lands at the same place in every view; the window's aspect is the view's.
  for (const glm::dvec3& p : {target, target + glm::dvec3(0.7, -0.3, 0), target + glm::dvec3(-1.1, 0.9, 0)}) {
    EXPECT_NEAR(glm::length(glm::dvec2(ndc(first, p)) - glm::dvec2(ndc(last, p))), 0.0, 1e-9);
    EXPECT_NEAR(glm::length(glm::dvec2(ndc(centre, p)) - glm::dvec2(ndc(last, p))), 0.0, 1e-9);
  }
  const double half_height = 5 * std::tan(fov / 2);
  EXPECT_NEAR(ndc(first, target + glm::dvec3(half_height * aspect, half_height, 0)).x, 1.0, 1e-9);
  EXPECT_NEAR(ndc(first, target + glm::dvec3(half_height * aspect, half_height, 0)).y, 1.0, 1e-9);
  // A point in front of the focal plane moves left as the camera moves right; one behind, right.
  const glm::dvec3 in_front = target + glm::dvec3(0, 0, 1), behind = target - glm::dvec3(0, 0, 1);
  EXPECT_GT(ndc(first, in_front).x, ndc(last, in_front).x);
  EXPECT_LT(ndc(first, behind).x, ndc(last, behind).x);
  // Two views stand at the two ends of the cone; a single view in its middle.
  EXPECT_NEAR(lightfield::quilt_view(eye, target, up, fov, aspect, 0.1, 50, 40, 0, 2).eye.x, first.eye.x, 1e-12);
  EXPECT_NEAR(lightfield::quilt_view(eye, target, up, fov, aspect, 0.1, 50, 40, 1, 2).eye.x, last.eye.x, 1e-12);
  EXPECT_NEAR(lightfield::quilt_view(eye, target, up, fov, aspect, 0.1, 50, 40, 0, 1).eye.x, 0.0, 1e-12);
}

// A subpixel exactly on a view boundary belongs to the view above it, and with inverted views the
// fraction 1 - 0 = 1 still names the last view, never one past it.
TEST(LightfieldQuilt, ABoundarySubpixelNamesAViewThatExists) {
  lightfield::Calibration c;
  c.screen_width = 1;
  c.screen_height = 1;
  lightfield::Interleave i;
  i.pitch = 1.0;
  i.center = 0.5;  // pixel (0, 0)'s centre u = 0.5: phase 0 exactly
  i.views = 8;
  EXPECT_EQ(lightfield::view_of_subpixel(i, c, 0, 0, 0), 0);
  i.inverted_views = true;
  EXPECT_EQ(lightfield::view_of_subpixel(i, c, 0, 0, 0), 7);
  i.center = 0.5 - 3.0 / 8;  // phase 3/8, inverted 5/8: view 5
  EXPECT_EQ(lightfield::view_of_subpixel(i, c, 0, 0, 0), 5);
  i.inverted_views = false;
  EXPECT_EQ(lightfield::view_of_subpixel(i, c, 0, 0, 0), 3);
}

// Display files: the examples in board/displays load as written; errors name file, line and key.
TEST(LightfieldDisplayFile, ExamplesLoadAsWritten) {
  lightfield::Display display;
  std::string error;
  ASSERT_TRUE(lightfield::load_display(PLAYER_BOARD_DIR "/displays/desk-8.toml", display, error)) << error;
  EXPECT_EQ(display.type, lightfield::DisplayType::modules);
  ASSERT_EQ(display.views(), 8);
  EXPECT_DOUBLE_EQ(display.modules.module_x.front(), -0.2);
  EXPECT_DOUBLE_EQ(display.modules.module_x.back(), 0.2);
  EXPECT_DOUBLE_EQ(display.modules.footprint.x, -0.2);  // default: the whole screen
  EXPECT_EQ(display.modules.width, 256);
  EXPECT_FALSE(display.modules.world_roi);

  ASSERT_TRUE(lightfield::load_display(PLAYER_BOARD_DIR "/displays/holovizio-c80.toml", display, error)) << error;
  EXPECT_EQ(display.views(), 80);
  EXPECT_NEAR(display.modules.module_x[1] - display.modules.module_x[0], 2.0 / 79, 1e-12);
  EXPECT_DOUBLE_EQ(display.modules.observer_height, 0.1);

  ASSERT_TRUE(lightfield::load_display(PLAYER_BOARD_DIR "/displays/looking-glass-portrait.toml", display, error)) << error;
  EXPECT_EQ(display.type, lightfield::DisplayType::quilt);
  EXPECT_EQ(display.views(), 45);
  EXPECT_EQ(display.quilt.view_width, 420);
  EXPECT_EQ(display.quilt.calibration.screen_width, 1536);
  EXPECT_DOUBLE_EQ(display.quilt.calibration.pitch, 52.58);
  EXPECT_TRUE(display.quilt.calibration.inverted_views);
  EXPECT_DOUBLE_EQ(display.quilt.calibration.view_cone_deg, 40.0);
}

std::string parse_error(const std::string& text) {
  lightfield::Display display;
  std::string error;
  EXPECT_FALSE(lightfield::parse_display(text, "/tmp/lf-test/d.toml", display, error)) << text;
  return error;
}

constexpr const char* kGood = R"(type = "modules"
[screen]
width = 1.6
height = 0.9
[observer]
distance = 2.5
[modules]
count = 4
x_first = -1.0
x_last = 1.0
z = -1.2
resolution = "64x36"
)";

// kGood, or `text`, with the first `from` replaced by `to`.
std::string replaced(std::string_view from, std::string_view to, std::string text = kGood) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

TEST(LightfieldDisplayFile, ErrorsNameFileLineAndKey) {
  lightfield::Display display;
  std::string error;
  ASSERT_TRUE(lightfield::parse_display(kGood, "d.toml", display, error)) << error;
  EXPECT_EQ(display.views(), 4);
  EXPECT_EQ(display.modules.observer_height, 0.0) << "the observer line's height when the file gives none";
  EXPECT_EQ(parse_error(replaced("count = 4", "count = 0")),
            "/tmp/lf-test/d.toml:8:9: modules.count: expected an integer in 1..1024, got 0");
  EXPECT_EQ(
      parse_error(replaced("\"64x36\"", "\"64by36\"")),
      "/tmp/lf-test/d.toml:12:14: modules.resolution: expected each module's image size as \"WxH\", each 1..16384, got '64by36'");
  EXPECT_EQ(parse_error(replaced("z = -1.2", "z = 0.5")),
            "/tmp/lf-test/d.toml:11:5: modules.z: expected a number < 0 (the modules stand behind the screen), got 0.5");
  EXPECT_EQ(parse_error(replaced("width = 1.6", "widht = 1.6")),
            "/tmp/lf-test/d.toml:3:9: screen.widht: unknown key (expected one of width, height)");
  EXPECT_EQ(parse_error(replaced("type = \"modules\"", "type = \"hologram\"")),
            "/tmp/lf-test/d.toml:1:8: type: expected \"modules\" or \"quilt\", got 'hologram'");
  EXPECT_EQ(parse_error(replaced("[observer]\ndistance = 2.5\n", "")).substr(0, 43),
            "/tmp/lf-test/d.toml:1:1: observer: expected");
  EXPECT_EQ(parse_error(replaced("count = 4", "count = 3\nx = [0.0, 1.0]")),
            "/tmp/lf-test/d.toml:8:9: modules.count: expected the number of entries of modules.x (2), got 3");
  EXPECT_EQ(parse_error(replaced("count = 4", "x = [0.0, 1.0]")),
            "/tmp/lf-test/d.toml:9:11: modules.x_first: expected nothing when modules.x lists the positions, got -1");
  EXPECT_EQ(parse_error(std::string(kGood) + "[roi]\nphysical_min = [-0.5, -0.4, -1.5]\nphysical_max = [0.5, 0.4, 0.2]\n"),
            "/tmp/lf-test/d.toml:14:16: roi.physical_min: expected z above modules.z (-1.200000): the box lies in front of the "
            "modules, got array");
  EXPECT_EQ(parse_error("type = \"modules\"\n[screen\n").substr(0, 24), "/tmp/lf-test/d.toml:2:8:");
  EXPECT_EQ(parse_error(replaced("x_first = -1.0", "x_first = -1e300")),
            "/tmp/lf-test/d.toml:9:11: modules.x_first: expected a number of magnitude at most 1e6, got -1e+300");
}

// Each number's range holds at its ends as the error says: a screen or distance must be above zero,
// not zero; a magnitude of exactly 1e6 is accepted and one past it refused; the region in front of
// the modules must end before the observer line, not on it.
TEST(LightfieldDisplayFile, GeometryRangesHoldAtTheirEnds) {
  EXPECT_EQ(parse_error(replaced("width = 1.6", "width = 0")),
            "/tmp/lf-test/d.toml:3:9: screen.width: expected a number > 0, got 0");
  EXPECT_EQ(parse_error(replaced("distance = 2.5", "distance = 0.0")),
            "/tmp/lf-test/d.toml:6:12: observer.distance: expected a number > 0 (the observer line's distance from the screen), "
            "got 0");
  lightfield::Display display;
  std::string error;
  ASSERT_TRUE(
      lightfield::parse_display(replaced("distance = 2.5", "distance = 2.5\nheight = 1000000.0"), "d.toml", display, error))
      << error;
  EXPECT_EQ(display.modules.observer_height, 1e6);
  ASSERT_TRUE(
      lightfield::parse_display(replaced("distance = 2.5", "distance = 2.5\nheight = -1000000"), "d.toml", display, error))
      << error;
  EXPECT_EQ(display.modules.observer_height, -1e6);
  EXPECT_EQ(parse_error(replaced("distance = 2.5", "distance = 2.5\nheight = 1000000.5")),
            "/tmp/lf-test/d.toml:7:10: observer.height: expected a number of magnitude at most 1e6, got 1000000.5");

  const std::string roi = std::string(kGood) + "[roi]\nphysical_min = [-0.5, -0.4, -0.2]\n";
  EXPECT_EQ(parse_error(roi + "physical_max = [0.5, 0.4, 2.5]\n"),
            "/tmp/lf-test/d.toml:15:16: roi.physical_max: expected z below observer.distance (2.500000), got array");
  ASSERT_TRUE(lightfield::parse_display(roi + "physical_max = [0.5, 0.4, 2.4]\n", "d.toml", display, error)) << error;
  EXPECT_EQ(display.modules.physical_roi.max.z, 2.4);
}

// The modules' positions come either as a list or as a span, never both, and a span of one module
// has one position.
TEST(LightfieldDisplayFile, ModulePositionsAreGivenOneWayOnly) {
  const std::string listed = replaced("count = 4\nx_first = -1.0\nx_last = 1.0", "x = [0.0, 1.0]");
  EXPECT_EQ(parse_error(replaced("x = [0.0, 1.0]", "x = [0.0, 1.0]\nx_last = 1.0", listed)),
            "/tmp/lf-test/d.toml:9:10: modules.x_last: expected nothing when modules.x lists the positions, got 1");
  EXPECT_EQ(parse_error(replaced("x = [0.0, 1.0]", "x = [0.0, 1.0]\nx_first = 0.0", listed)),
            "/tmp/lf-test/d.toml:9:11: modules.x_first: expected nothing when modules.x lists the positions, got 0");
  EXPECT_EQ(parse_error(replaced("count = 4", "count = 1")),
            "/tmp/lf-test/d.toml:10:10: modules.x_last: expected x_first when there is one module, got 1");
}

// Every module's image goes into one montage texture: module count times resolution is checked in
// the file, before anything is allocated, where a terabyte montage once reached the GPU.
TEST(LightfieldDisplayFile, AMontageBeyondATexturesSideIsRefusedByTheFile) {
  const std::string huge = replaced("\"64x36\"", "\"16384x16384\"", replaced("count = 4", "count = 1024"));
  EXPECT_EQ(parse_error(huge),
            "/tmp/lf-test/d.toml:12:14: modules.resolution: expected a montage of at most 16384 pixels per side: 1024 modules "
            "of this size make 524288x524288 (32x32 modules), got '16384x16384'");
  // Just within: 4 modules of 8192x8192 make a 16384x16384 montage; one pixel wider is refused.
  lightfield::Display display;
  std::string error;
  EXPECT_TRUE(lightfield::parse_display(replaced("\"64x36\"", "\"8192x8192\""), "d.toml", display, error)) << error;
  EXPECT_EQ(
      parse_error(replaced("\"64x36\"", "\"8193x8192\""))
          .rfind(
              "/tmp/lf-test/d.toml:12:14: modules.resolution: expected a montage of at most 16384 pixels per side: 4 modules of "
              "this size make 16386x16384",
              0),
      0u);
  // A quilt likewise, too wide or too tall alone: 64 columns of 257 pixels, or 64 rows.
  const std::string quilt = "type = \"quilt\"\ncalibration = \"visual.json\"\n";
  const std::string quilt_error =
      "/tmp/lf-test/d.toml:4:13: view_size: expected a quilt of at most 16384 pixels per side (columns x width, rows x "
      "height), got ";
  EXPECT_EQ(parse_error(quilt + "quilt = \"64x1\"\nview_size = \"257x100\"\n"), quilt_error + "'257x100'");
  EXPECT_EQ(parse_error(quilt + "quilt = \"1x64\"\nview_size = \"100x257\"\n"), quilt_error + "'100x257'");
  EXPECT_EQ(parse_error(quilt + "quilt = \"5x9\"\nview_size = \"420x560\"\nview_cone = 40\n"),
            "/tmp/lf-test/d.toml:5:13: view_cone: unknown key (expected one of type, calibration, quilt, view_size)");
  // At the limit the calibration is what is missing, not the size.
  EXPECT_EQ(parse_error(quilt + "quilt = \"64x64\"\nview_size = \"256x256\"\n").find("calibration: expected a readable"),
            std::string("/tmp/lf-test/d.toml:2:15: ").size());
}

// Every list is checked for its length at both ends, every box on each of its three axes, and a
// region given is the one used: a file that is wrong in its last axis or its last entry is refused
// as surely as one wrong in its first.
TEST(LightfieldDisplayFile, ListsAndBoxesAreCheckedInFullAndReadAsWritten) {
  const std::string roi = std::string(kGood) + "[roi]\n";
  EXPECT_EQ(parse_error(roi + "physical_min = [-0.5, -0.4, -0.2, 0.0]\nphysical_max = [0.5, 0.4, 0.2]\n"),
            "/tmp/lf-test/d.toml:14:16: roi.physical_min: expected three numbers [x, y, z], got array");
  EXPECT_EQ(parse_error(roi + "physical_min = [-0.5, -0.4]\nphysical_max = [0.5, 0.4, 0.2]\n"),
            "/tmp/lf-test/d.toml:14:16: roi.physical_min: expected three numbers [x, y, z], got array");
  const std::string footprint_error =
      "/tmp/lf-test/d.toml:12:13: modules.footprint: expected two numbers [x0, x1] with x0 < x1, got array";
  EXPECT_EQ(parse_error(replaced("z = -1.2", "z = -1.2\nfootprint = [-0.5]")), footprint_error);
  EXPECT_EQ(parse_error(replaced("z = -1.2", "z = -1.2\nfootprint = [-0.5, 0.0, 0.5]")), footprint_error);
  EXPECT_EQ(parse_error(replaced("z = -1.2", "z = -1.2\nfootprint = [0.5, 0.5]")), footprint_error);
  EXPECT_EQ(parse_error(replaced("z = -1.2", "z = -1.2\nfootprint = [0.5, -0.5]")), footprint_error);

  // A box flat or inverted in any one axis, the others fine.
  for (int axis = 0; axis < 3; ++axis) {
    std::string max = "[1.0, 2.0, 3.0]";
    max.replace(1 + 5 * axis, 3, "0.0");
    EXPECT_EQ(parse_error(roi + "world_min = [0.0, 0.0, 0.0]\nworld_max = " + max + "\n"),
              "/tmp/lf-test/d.toml:15:13: roi.world_max: expected a point above roi.world_min on every axis, got array")
        << "axis " << axis;
    std::string physical_max = "[0.5, 0.4, 0.2]";
    physical_max.replace(1 + 5 * axis, 3, axis == 0 ? "-0.5" : axis == 1 ? "-0.4" : "-0.2");
    EXPECT_EQ(parse_error(roi + "physical_min = [-0.5, -0.4, -0.2]\nphysical_max = " + physical_max + "\n"),
              "/tmp/lf-test/d.toml:15:16: roi.physical_max: expected a point above roi.physical_min on every axis, got array")
        << "axis " << axis;
  }

  lightfield::Display display;
  std::string error;
  ASSERT_TRUE(lightfield::parse_display(roi + "world_min = [-1.0, -2.0, -3.0]\nworld_max = [1.0, 2.0, 3.0]\n"
                                              "physical_min = [-0.6, -0.3, -0.1]\nphysical_max = [0.7, 0.4, 0.2]\n",
                                        "d.toml", display, error))
      << error;
  ASSERT_TRUE(display.modules.world_roi.has_value());
  EXPECT_EQ(display.modules.world_roi->min, glm::dvec3(-1.0, -2.0, -3.0));
  EXPECT_EQ(display.modules.world_roi->max, glm::dvec3(1.0, 2.0, 3.0));
  EXPECT_EQ(display.modules.physical_roi.min, glm::dvec3(-0.6, -0.3, -0.1));
  EXPECT_EQ(display.modules.physical_roi.max, glm::dvec3(0.7, 0.4, 0.2));
  ASSERT_TRUE(lightfield::parse_display(replaced("z = -1.2", "z = -1.2\nfootprint = [-0.5, 0.25]"), "d.toml", display, error))
      << error;
  EXPECT_EQ(display.modules.footprint, glm::dvec2(-0.5, 0.25));
  EXPECT_FALSE(display.modules.world_roi.has_value()) << "a file without a world box after one with it";
  // Without a box: the screen's rectangle, a quarter of its smaller side deep on each side.
  EXPECT_EQ(display.modules.physical_roi.min, glm::dvec3(-0.8, -0.45, -0.225));
  EXPECT_EQ(display.modules.physical_roi.max, glm::dvec3(0.8, 0.45, 0.225));

  // One module, listed or spanned.
  ASSERT_TRUE(lightfield::parse_display(replaced("count = 4\nx_first = -1.0\nx_last = 1.0", "count = 1\nx = [0.3]"), "d.toml",
                                        display, error))
      << error;
  EXPECT_EQ(display.modules.module_x, std::vector<double>{0.3});
  ASSERT_TRUE(lightfield::parse_display(
      replaced("count = 4", "count = 1", replaced("x_first = -1.0\nx_last = 1.0", "x_first = 0.3\nx_last = 0.3")), "d.toml",
      display, error))
      << error;
  EXPECT_EQ(display.modules.module_x, std::vector<double>{0.3});
  EXPECT_EQ(parse_error(replaced("count = 4", "x = [0.0, \"0.5\"]")),
            "/tmp/lf-test/d.toml:8:11: modules.x: expected 1..1024 numbers, one x per module, got '0.5'");
  EXPECT_EQ(parse_error(replaced("count = 4\nx_first = -1.0\nx_last = 1.0", "count = 0\nx = [0.3]")),
            "/tmp/lf-test/d.toml:8:9: modules.count: expected an integer in 1..1024, got 0");
  EXPECT_EQ(parse_error(replaced("count = 4\n", "")).substr(0, 76),
            "/tmp/lf-test/d.toml:7:1: modules.count: expected an integer in 1..1024, got ");
  EXPECT_EQ(parse_error(roi + "world_max = [1.0, 2.0, 3.0]\n"),
            "/tmp/lf-test/d.toml:13:1: roi.world_min: expected three numbers [x, y, z], got nothing");
  EXPECT_EQ(parse_error(replaced("distance = 2.5", "distance = 2.5\nhieght = 0.1")),
            "/tmp/lf-test/d.toml:7:10: observer.hieght: unknown key (expected one of distance, height)");
}

// The calibration's ranges hold at their ends: what docs/light-field.md says is accepted is, and a
// step past it is refused.
TEST(LightfieldDisplayFile, CalibrationRangesHoldAtTheirEnds) {
  // A valid calibration with some fields replaced or added.
  const auto calibration = [](std::map<std::string, std::string> changed) {
    std::map<std::string, std::string> fields{{"pitch", "50"}, {"slope", "-5"},    {"center", "0.1"},
                                              {"DPI", "300"},  {"screenW", "100"}, {"screenH", "50"}};
    for (const auto& [key, value] : changed) fields[key] = value;
    std::string json;
    for (const auto& [key, value] : fields) json += (json.empty() ? "{" : ", ") + ("\"" + key + "\": {\"value\": " + value + "}");
    return json + "}";
  };
  const auto accepted = [&](const std::map<std::string, std::string>& changed, lightfield::Calibration& c) {
    std::string error;
    const bool ok = lightfield::parse_calibration(calibration(changed), "v.json", c, error);
    EXPECT_TRUE(ok) << calibration(changed) << ": " << error;
    return ok;
  };
  const auto refused = [&](const std::map<std::string, std::string>& changed) {
    lightfield::Calibration c;
    std::string error;
    EXPECT_FALSE(lightfield::parse_calibration(calibration(changed), "v.json", c, error)) << calibration(changed);
    return error;
  };
  lightfield::Calibration c;
  EXPECT_TRUE(accepted({{"DPI", "1"}}, c));
  EXPECT_EQ(c.dpi, 1.0);
  EXPECT_EQ(c.view_cone_deg, 40.0) << "the view cone when the file gives none";
  EXPECT_FALSE(c.inverted_views || c.flip_x || c.flip_y) << "the flags when the file gives none";
  EXPECT_EQ(refused({{"DPI", "0.999"}}), "v.json: DPI: expected an object {\"value\": number in 1..1e6}, got \"value\": 0.999");
  EXPECT_TRUE(accepted({{"screenW", "16384"}, {"screenH", "1"}}, c));
  EXPECT_EQ(c.screen_width, 16384);
  EXPECT_EQ(c.screen_height, 1);
  EXPECT_EQ(refused({{"screenW", "16385"}}),
            "v.json: screenW: expected an object {\"value\": number (an integer in 1..16384)}, got \"value\": 16385");
  EXPECT_TRUE(accepted({{"viewCone", "179.5"}, {"invView", "0"}, {"flipImageX", "1"}}, c));
  EXPECT_EQ(c.view_cone_deg, 179.5);
  EXPECT_FALSE(c.inverted_views);
  EXPECT_TRUE(c.flip_x);
  EXPECT_EQ(refused({{"viewCone", "180"}}),
            "v.json: viewCone: expected an object {\"value\": number (degrees, in (0, 180))}, got \"value\": 180");
  EXPECT_EQ(refused({{"invView", "2"}}), "v.json: invView: expected an object {\"value\": number (0 or 1)}, got \"value\": 2");
  EXPECT_TRUE(accepted({{"slope", "-1e-6"}, {"pitch", "1e6"}}, c));
  EXPECT_EQ(c.slope, -1e-6);
  EXPECT_EQ(refused({{"pitch", "0"}}), "v.json: pitch: expected an object {\"value\": number in (0, 1e6]}, got \"value\": 0");
  // The range is open at 0 only: a coarse lens sheet has less than one lenticule per inch.
  EXPECT_TRUE(accepted({{"pitch", "0.25"}}, c));
  EXPECT_EQ(c.pitch, 0.25);
  EXPECT_TRUE(accepted({{"center", "1e6"}}, c));
  EXPECT_TRUE(accepted({{"center", "-1e6"}}, c));
  EXPECT_EQ(c.center, -1e6);
  EXPECT_EQ(refused({{"center", "1000000.5"}}),
            "v.json: center: expected an object {\"value\": number of magnitude at most 1e6}, got \"value\": 1000000.5");
}

// A display file or calibration as large as the limit loads; a byte more is refused before it is
// parsed, with both sizes named.
TEST(LightfieldDisplayFile, AFileAtTheSizeLimitLoadsAndOneByteMoreIsRefused) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "lightfield-size-test";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "d.toml").string();
  std::string text = std::string(kGood) + "# ";
  text += std::string(lightfield::kMaxDisplayFileBytes - text.size() - 1, 'x') + "\n";
  ASSERT_EQ(text.size(), lightfield::kMaxDisplayFileBytes);
  std::ofstream(path, std::ios::binary) << text;
  lightfield::Display display;
  std::string error;
  EXPECT_TRUE(lightfield::load_display(path, display, error)) << error;
  EXPECT_EQ(display.views(), 4);
  std::ofstream(path, std::ios::binary) << text << "\n";
  EXPECT_FALSE(lightfield::load_display(path, display, error));
  EXPECT_EQ(error, path + ": the display file is 1.0 MiB (1048577 bytes); at most 1.0 MiB (1048576 bytes) is read");
  std::filesystem::remove_all(dir);
}

TEST(LightfieldDisplayFile, QuiltCalibrationErrorsNameTheField) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "lightfield-test";
  std::filesystem::create_directories(dir);
  const std::string display_path = (dir / "q.toml").string();
  std::ofstream(dir / "visual.json") << R"({"pitch": {"value": 50}, "slope": {"value": -5}, "center": {"value": 0.1},
    "DPI": {"value": 300}, "screenW": {"value": 100}, "screenH": {"value": "fifty"}})";
  lightfield::Display display;
  std::string error;
  EXPECT_FALSE(lightfield::parse_display(
      "type = \"quilt\"\ncalibration = \"visual.json\"\nquilt = \"2x2\"\nview_size = \"50x25\"\n", display_path, display, error));
  EXPECT_EQ(error,
            (dir / "visual.json").string() +
                ": screenH: expected an object {\"value\": number (an integer in 1..16384)}, got \"value\" of type string");
  EXPECT_FALSE(lightfield::parse_display(
      "type = \"quilt\"\ncalibration = \"absent.json\"\nquilt = \"2x2\"\nview_size = \"50x25\"\n", display_path, display, error));
  EXPECT_EQ(error, display_path + ":2:15: calibration: expected a readable regular file (" + (dir / "absent.json").string() +
                       ": cannot open the calibration (No such file or directory)), got 'absent.json'");
  EXPECT_FALSE(lightfield::parse_display("type = \"quilt\"\ncalibration = \"v.json\"\nquilt = \"65x2\"\nview_size = \"50x25\"\n",
                                         display_path, display, error));
  EXPECT_EQ(error, display_path + ":3:9: quilt: expected columns x rows of views as \"WxH\", each 1..64, got '65x2'");
  lightfield::Calibration c;
  EXPECT_FALSE(lightfield::parse_calibration("[1, 2]", "v.json", c, error));
  EXPECT_EQ(error, "v.json: expected a JSON object (the display's visual.json)");
  EXPECT_FALSE(lightfield::parse_calibration(R"({"pitch": 50})", "v.json", c, error));
  EXPECT_EQ(error, "v.json: pitch: expected an object {\"value\": number in (0, 1e6]}, got number");
  EXPECT_FALSE(lightfield::parse_calibration(R"({"pitch": {"value": 50}, "slope": {"value": 1e-300}})", "v.json", c, error));
  EXPECT_EQ(error, "v.json: slope: expected an object {\"value\": number of magnitude 1e-6..1e6}, got \"value\": 1e-300");
  std::filesystem::remove_all(dir);
}

}  // namespace
