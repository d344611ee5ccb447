// Light field output on a real context: the lenticular interleave checked at every panel subpixel with
// the view probe, the quilt's tile order, module skipping, the positions texture's round trip through
// the module's world-to-image transform, and Algorithm 2 against Algorithm 1 where they must agree.
#include "render/light_field.h"
#include "gl/caps.h"
#include "gl/gl_api.h"
#include "harness.h"
#include "lightfield/display_file.h"
#include "platform/platform.h"
#include "render/readback.h"
#include "render/renderer.h"
#include "scene/load.h"
#include "scene/procedural.h"

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

namespace {

// A 1.6 x 0.9 screen watched from 2.5 away, up to the [modules] table, which each test fills in.
constexpr const char* kDeskModules = R"(type = "modules"
[screen]
width = 1.6
height = 0.9
[observer]
distance = 2.5
[modules]
)";

class LightField : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    std::string error;
    session_ = test::open_session(GetParam(), 64, 64, error);
    ASSERT_TRUE(session_) << error;
    dir_ = std::filesystem::temp_directory_path() / ("light-field-test-" + GetParam());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  lightfield::Display display(const std::string& toml, const std::string& visual_json = "") {
    if (!visual_json.empty()) std::ofstream(dir_ / "visual.json") << visual_json;
    lightfield::Display out;
    std::string error;
    EXPECT_TRUE(lightfield::parse_display(toml, (dir_ / "display.toml").string(), out, error)) << error;
    return out;
  }

  ::testing::AssertionResult start(render::LightFieldRenderer& renderer, const scene::Scene& scene, const lightfield::Display& d,
                                   render::FrameSettings settings = {}) {
    std::string error;
    settings.check_errors = true;
    const scene::Camera camera = scene::frame(scene.bounds, {}, d.quilt.view_width, d.quilt.view_height);
    if (!renderer.init(*session_, error) || !renderer.upload(scene, error) || !renderer.configure(d, settings, camera, error))
      return ::testing::AssertionFailure() << error;
    return ::testing::AssertionSuccess();
  }

  std::unique_ptr<gl::Session> session_;
  std::filesystem::path dir_;
};

scene::Scene builtin(const std::string& name) {
  scene::Scene scene;
  std::string error;
  std::ostringstream log;
  EXPECT_TRUE(scene::load("builtin:" + name, scene, error, log)) << error;
  return scene;
}

constexpr const char* kQuilt = "type = \"quilt\"\ncalibration = \"visual.json\"\nquilt = \"4x3\"\nview_size = \"20x15\"\n";

std::string calibration(int inverted, int flip_x) {
  return R"({"pitch": {"value": 50}, "slope": {"value": -5}, "center": {"value": 0.1}, "DPI": {"value": 300},
             "screenW": {"value": 120}, "screenH": {"value": 90}, "invView": {"value": )" +
         std::to_string(inverted) + R"(}, "flipImageX": {"value": )" + std::to_string(flip_x) + "}}";
}

TEST_P(LightField, ProbeShowsTheCalibrationsViewAtEveryPanelSubpixel) {
  for (const auto& [inverted, flip_x] : {std::pair{0, 0}, std::pair{1, 0}, std::pair{0, 1}}) {
    const lightfield::Display d = display(kQuilt, calibration(inverted, flip_x));
    render::LightFieldRenderer renderer;
    ASSERT_TRUE(start(renderer, builtin("corner"), d));
    renderer.output().set_probe(true);
    renderer.render();
    ASSERT_EQ(renderer.gl_error(), "");
    const std::vector<uint8_t> native = renderer.output().read_native();
    const lightfield::Calibration& c = d.quilt.calibration;
    const lightfield::Interleave interleave = lightfield::interleave_of(c, 12);
    ASSERT_EQ(native.size(), 120u * 90u * 4u);
    int near_boundary = 0;
    for (int row = 0; row < 90; ++row)
      for (int x = 0; x < 120; ++x)
        for (int channel = 0; channel < 3; ++channel) {
          const int y = 89 - row;  // the formula counts rows from the bottom; the read-back is top first
          const int shown = native[(static_cast<size_t>(row) * 120 + static_cast<size_t>(x)) * 4 + static_cast<size_t>(channel)];
          const int expected = lightfield::view_of_subpixel(interleave, c, x, y, channel);
          // The shader's fract() runs in float: a phase of ~20 carries ~2e-6 of rounding, so a subpixel
          // whose z * N lies within 1e-3 of a whole number may fall on either side of it.
          const double position = lightfield::view_fraction(interleave, c, x, y, channel) * 12.0;
          if (std::abs(position - std::round(position)) < 1e-3) {
            ++near_boundary;
            EXPECT_LE(std::abs(shown - expected), 1) << x << "," << y << " channel " << channel;
            continue;
          }
          ASSERT_EQ(shown, expected) << "subpixel " << x << "," << y << " channel " << channel << " invView " << inverted
                                     << " flipImageX " << flip_x;
        }
    EXPECT_LT(near_boundary, 120 * 90 * 3 / 100);
  }
}

TEST_P(LightField, QuiltTilesHoldTheirViewsFromTheBottomLeft) {
  const lightfield::Display d = display(kQuilt, calibration(0, 0));
  render::LightFieldRenderer renderer;
  ASSERT_TRUE(start(renderer, builtin("corner"), d));
  renderer.output().set_probe(true);
  renderer.render();
  ASSERT_EQ(renderer.output().output_size(), glm::ivec2(80, 45));
  const std::vector<uint8_t> quilt = renderer.output().read_output();
  for (int row = 0; row < 45; ++row)
    for (int x = 0; x < 80; ++x) {
      const int tile_column = x / 20, tile_row_from_bottom = (44 - row) / 15;
      const int view = tile_row_from_bottom * 4 + tile_column;
      ASSERT_EQ(quilt[(static_cast<size_t>(row) * 80 + static_cast<size_t>(x)) * 4], view) << x << "," << row;
    }
  // The scene itself: every view shows it, and neighbouring views differ (parallax).
  renderer.output().set_probe(false);
  renderer.render();
  ASSERT_EQ(renderer.gl_error(), "");
  EXPECT_NE(renderer.output().read_view(0), renderer.output().read_view(11));
}

// Modules whose image the scene cannot reach are not rendered and show the background.
TEST_P(LightField, ModulesThatSeeNothingAreSkipped) {
  const lightfield::Display d = display(std::string(kDeskModules) + R"(count = 16
x_first = -1.0
x_last = 1.0
z = -1.2
resolution = "32x18"
footprint = [0.55, 0.8]
[roi]
physical_min = [0.3, -0.1, -0.1]
physical_max = [0.5, 0.1, 0.1]
)");
  render::LightFieldRenderer renderer;
  render::FrameSettings settings;
  settings.ao_settings.estimator = ssao::Estimator::sphere;
  ASSERT_TRUE(start(renderer, builtin("corner"), d, settings));
  renderer.render();
  ASSERT_EQ(renderer.gl_error(), "");
  EXPECT_GT(renderer.output().rendered_views(), 0);
  EXPECT_LT(renderer.output().rendered_views(), 16);
  EXPECT_FALSE(renderer.output().skipped(0));  // by hand, in unit.LightfieldModules.SeesExactlyTheModulesWhoseImageTheBoxReaches
  EXPECT_TRUE(renderer.output().skipped(15));
  const std::vector<uint8_t> background = renderer.output().read_view(15);
  const scene::Scene scene = builtin("corner");
  int showing = 0;
  for (int k = 0; k < 16; ++k) {
    const std::vector<uint8_t> image = renderer.output().read_view(k);
    if (!renderer.output().skipped(k)) {
      showing += image != background ? 1 : 0;
      continue;
    }
    EXPECT_EQ(image, background) << "module " << k;
    // Skipped for a reason: no vertex of the scene lands in the module's image.
    const render::ModuleView& module = *renderer.output().view(k).module;
    for (const scene::Instance& instance : scene.instances)
      for (const scene::Vertex& vertex : scene.meshes[static_cast<size_t>(instance.mesh)].vertices) {
        const glm::dvec3 world(instance.world * glm::dvec4(glm::dvec3(vertex.position), 1.0));
        const auto image_point = lightfield::physical_to_image(module.module, module.roi.to_physical(world));
        if (!image_point) continue;
        ASSERT_FALSE(image_point->x >= 0 && image_point->x <= 32 && image_point->y >= 0 && image_point->y <= 18)
            << "module " << k;
      }
  }
  EXPECT_GT(showing, 0);
}

// Every object pixel's world position, mapped by the module's world-to-image transform, lands back
// on that pixel: the rasteriser put each surface point where the module shows it. builtin:corner's
// three squares are two triangles each, whose edges the per-vertex transform bends by up to 22
// pixels on the C80 geometry: the renderer splits them first.
TEST_P(LightField, PositionsTextureMapsBackToItsOwnPixel) {
  for (const auto& [file, scene_name] : {std::pair{"desk-8.toml", "demo"}, std::pair{"holovizio-c80.toml", "corner"}}) {
    lightfield::Display d;
    std::string error;
    ASSERT_TRUE(lightfield::load_display(std::string(PLAYER_BOARD_DIR "/displays/") + file, d, error)) << error;
    if (d.views() > 8) {  // eight modules spread over the row, ends included, keep the test short
      std::vector<double> x;
      for (int i = 0; i < 8; ++i) x.push_back(d.modules.module_x[static_cast<size_t>(i * (d.views() - 1) / 7)]);
      d.modules.module_x = x;
    }
    render::LightFieldRenderer renderer;
    render::FrameSettings settings;
    settings.ao_settings.estimator = ssao::Estimator::hemisphere;
    ASSERT_TRUE(start(renderer, builtin(scene_name), d, settings));
    if (std::string(scene_name) == "corner") {
      EXPECT_GT(renderer.subdivision().worst_before_px, 5.0);
      EXPECT_GT(renderer.subdivision().triangles_after, renderer.subdivision().triangles_before);
      EXPECT_LE(renderer.subdivision().worst_after_px, 0.5);
    }
    double worst = 0.0;
    long objects = 0;
    renderer.output().set_after_view([&](int k, const render::View& view, const render::ViewTargets& targets) {
      const render::WorldSurface surface = render::read_module_surface(targets);
      for (int y = 0; y < surface.height; ++y)
        for (int x = 0; x < surface.width; ++x) {
          const size_t i = (static_cast<size_t>(y) * static_cast<size_t>(surface.width) + static_cast<size_t>(x)) * 4;
          if (surface.position[i + 3] <= 0.0f) continue;
          ++objects;
          const glm::dvec3 world(surface.position[i], surface.position[i + 1], surface.position[i + 2]);
          const auto image = lightfield::physical_to_image(view.module->module, view.module->roi.to_physical(world));
          ASSERT_TRUE(image) << "module " << k;
          // Image rows run from the top; the read-back's from the bottom.
          const glm::dvec2 centre(x + 0.5, surface.height - y - 0.5);
          worst = std::max(worst, glm::length(glm::dvec2(*image) - centre));
        }
    });
    renderer.render();
    ASSERT_EQ(renderer.gl_error(), "");
    EXPECT_GT(objects, static_cast<long>(d.modules.width) * d.modules.height * 8 / 20) << file;
    // The edge bound (0.5 px) plus float rounding of the interpolated position.
    EXPECT_LT(worst, 0.52) << file << ": a surface point is drawn this many pixels from where its module shows it";
    std::cout << file << " " << scene_name << ": worst " << worst << " px over " << objects << " pixels\n";
  }
}

// With the module and the observer line a thousand screen heights away, the module's world-to-image
// transform tends to the projection of a far camera on the observer line: Algorithm 2 must then give
// what Algorithm 1 gives. A box standing out of a wall: contact corners around it, open faces beside.
// The physical box is half the world box, so radii and depths must be scaled on the way.
TEST_P(LightField, Algorithm2OnAFlatScreenModuleAgreesWithAlgorithm1) {
  scene::Scene scene;
  scene.name = "box on a wall";
  scene.materials.push_back({});
  scene::add_instance(scene, scene::make_quad({-1.0f, -0.75f, 0.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 1.5f, 0.0f}, 0));
  scene::add_instance(scene, scene::make_box({-0.3f, -0.3f, 0.0f}, {0.3f, 0.3f, 0.4f}, 0));
  scene::update_bounds(scene);
  const lightfield::Display d = display(R"(type = "modules"
[screen]
width = 1.0
height = 0.75
[observer]
distance = 1000.0
[modules]
count = 1
x_first = 0.0
x_last = 0.0
z = -1000.0
resolution = "128x96"
[roi]
world_min = [-1.0, -0.75, -0.5]
world_max = [1.0, 0.75, 0.5]
physical_min = [-0.5, -0.375, -0.25]
physical_max = [0.5, 0.375, 0.25]
)");
  render::FrameSettings settings;
  settings.width = 128;
  settings.height = 96;
  settings.ao_settings.estimator = ssao::Estimator::sphere;
  settings.ao_settings.samples = 32;
  settings.ao_settings.depth_chain = false;
  settings.ao_settings.skip_radii = false;
  settings.ao_settings.half_resolution = false;
  settings.blur.mode = ssao::Blur::off;
  settings.radius = 0.15f;
  std::vector<glm::vec2> module_ao;
  std::vector<float> module_depth;
  render::LightFieldRenderer lf;
  ASSERT_TRUE(start(lf, scene, d, settings));
  lf.output().set_after_view([&](int, const render::View&, const render::ViewTargets& targets) {
    module_ao = render::read_ao(targets.ao_raw, 128, 96);
    module_depth = render::read_linear_depth(targets);
  });
  lf.render();
  ASSERT_EQ(lf.gl_error(), "");

  render::Renderer renderer;
  std::string error;
  settings.check_errors = true;
  ASSERT_TRUE(
      renderer.init(*session_, {session_->platform().framebuffer(), 0, 0, session_->platform().srgb_framebuffer()}, error) &&
      renderer.upload(scene, error) && renderer.configure(settings, error))
      << error;
  render::View camera;
  camera.eye = {0.0, 0.0, 2000.0};  // the observer line, in world units
  camera.view = glm::lookAt(camera.eye, glm::dvec3(0.0), glm::dvec3(0, 1, 0));
  camera.near = 1996.0;
  camera.far = 2004.0;
  camera.projection = glm::perspective(2.0 * std::atan(0.75 / 2000.0), 4.0 / 3.0, camera.near, camera.far);
  renderer.render(camera);
  ASSERT_EQ(renderer.gl_error(), "");
  const std::vector<glm::vec2> camera_ao = renderer.read_ao_raw();
  const std::vector<float> camera_depth = renderer.read_linear_depth();

  // The same surface at the same pixels: depth from the observer line (physical) is half the depth
  // from the camera (world).
  double depth_error = 0.0, sum_module = 0.0, sum_camera = 0.0, worst_block = 0.0;
  int objects = 0;
  for (size_t i = 0; i < camera_depth.size(); ++i) {
    if (camera_depth[i] <= 0.0f || module_depth[i] <= 0.0f) continue;
    depth_error = std::max(depth_error, static_cast<double>(std::abs(camera_depth[i] - 2.0f * module_depth[i])));
    sum_module += module_ao[i].x;
    sum_camera += camera_ao[i].x;
    ++objects;
  }
  // The two turn the same kernel differently (Algorithm 1 by a 4x4 pixel tile, Algorithm 2 by world
  // cells), so single pixels differ by sampling noise; means over 8x8 blocks agree to 0.011 at worst
  // (measured on both platforms) and the image means to 1e-5. The bounds leave about three times that.
  for (int by = 0; by < 96; by += 8)
    for (int bx = 0; bx < 128; bx += 8) {
      double a = 0.0, b = 0.0;
      for (int y = by; y < by + 8; ++y)
        for (int x = bx; x < bx + 8; ++x) {
          a += module_ao[static_cast<size_t>(y * 128 + x)].x;
          b += camera_ao[static_cast<size_t>(y * 128 + x)].x;
        }
      worst_block = std::max(worst_block, std::abs(a - b) / 64.0);
    }
  EXPECT_EQ(objects, 128 * 96);  // the wall fills the image
  EXPECT_LT(depth_error, 2e-3);  // float depth at 2000 keeps 1.2e-4; the two horizontal perspectives differ by 1e-3 over the box
  EXPECT_NEAR(sum_module / objects, sum_camera / objects, 0.003);
  EXPECT_LT(worst_block, 0.03);
  std::cout << "mean AO: Algorithm 2 " << sum_module / objects << ", Algorithm 1 " << sum_camera / objects << "; worst 8x8 block "
            << worst_block << "; depth " << depth_error << "\n";
}

// What play shows: the output presented onto the surface keeps its bytes, on an sRGB surface (egl's)
// as on a plain one (osmesa's), letterboxed in black.
TEST_P(LightField, PresentKeepsTheOutputsBytesOnTheSurface) {
  const lightfield::Display d = display(std::string(kDeskModules) + R"(count = 1
x_first = 0.0
x_last = 0.0
z = -1.2
resolution = "64x36"
)");
  render::LightFieldRenderer renderer;
  render::FrameSettings settings;
  settings.ao_settings.estimator = ssao::Estimator::hemisphere;
  ASSERT_TRUE(start(renderer, builtin("demo"), d, settings));
  renderer.render();
  const render::PresentTarget surface{session_->platform().framebuffer(), 0, 0, session_->platform().srgb_framebuffer()};
  renderer.present(surface, 64, 64);
  ASSERT_EQ(renderer.gl_error(), "");
  const std::vector<uint8_t> output = renderer.output().read_output(), shown = render::read_presented(surface, 64, 64);
  for (int row = 0; row < 64; ++row)
    for (int x = 0; x < 64; ++x) {
      const size_t at = (static_cast<size_t>(row) * 64 + static_cast<size_t>(x)) * 4;
      const int inside = row - 14;  // 36 rows centred in 64
      for (int c = 0; c < 3; ++c) {
        const int expected =
            inside >= 0 && inside < 36
                ? output[(static_cast<size_t>(inside) * 64 + static_cast<size_t>(x)) * 4 + static_cast<size_t>(c)]
                : 0;
        ASSERT_EQ(shown[at + static_cast<size_t>(c)], expected) << x << "," << row << " channel " << c;
      }
    }
}

INSTANTIATE_TEST_SUITE_P(Platforms, LightField, ::testing::Values("egl", "osmesa"),
                         [](const auto& param) { return param.param; });

}  // namespace
