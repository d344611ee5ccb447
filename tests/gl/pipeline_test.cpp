// The GPU pipeline against the CPU reference and against values known in closed form, on both
// headless platforms.
#include "harness.h"
#include "scene/procedural.h"
#include "ssao/reference.h"

#include <algorithm>

namespace {

using test::Harness;

constexpr int kSide = 64;

render::FrameSettings small_settings() {
  render::FrameSettings settings;
  settings.width = settings.height = kSide;
  settings.check_errors = true;
  // These tests read the AO pixel for pixel against the G-buffer; half resolution has its own cases.
  settings.ao_settings.half_resolution = false;
  return settings;
}

class Pipeline : public ::testing::TestWithParam<std::string> {};

struct Comparison {
  float max_difference = 0.0f;
  size_t off_by_more = 0;  // pixels differing by more than `tolerance`
};

Comparison compare(const std::vector<glm::vec2>& gpu, const std::vector<glm::vec2>& cpu, float tolerance) {
  Comparison result;
  for (size_t i = 0; i < gpu.size(); ++i) {
    const float difference = std::abs(gpu[i].x - cpu[i].x);
    result.max_difference = std::max(result.max_difference, difference);
    if (difference > tolerance) ++result.off_by_more;
  }
  return result;
}

// The GPU's result against the CPU reference fed the GPU's own G-buffer (depth and normals), so both
// see the very same per-pixel inputs.
// Point-sampled estimators (sphere, hemisphere): the two evaluate the same float expressions in
// possibly different order, so a sample lying within rounding of a depth or texel boundary may flip:
// that moves one pixel's AO by one sample's weight (1/samples). Allowed at up to 1% of pixels; all
// others agree to half-float precision.
// Horizon: its AO is continuous in the tap depths, and the only discontinuities (a tap's texel,
// floor(offset + 0.5), and the radius cutoff) need a tap within float rounding of a boundary, which
// none of these scenes has: measured on llvmpipe (egl and osmesa, full and half resolution, flat
// and chained depth), every pixel agrees to one half-float step (2^-11 = 0.00049 at AO in [0.5, 1),
// where both round to rgba16f) and the rest, llvmpipe's sin/cos/acos against libm's, stays under 1e-4.
// So every horizon pixel must agree to 1e-3: a sign flipped or a tap off by one anywhere in the
// estimator moves far more than that.
void expect_gpu_equals_reference(const Harness& h, const std::string& what, bool mediump_reference = false) {
  const render::FrameSettings& settings = h.renderer.settings();
  const ssao::Estimator estimator = settings.ao_settings.estimator;
  const bool bilateral = settings.blur.mode == ssao::Blur::bilateral;
  const auto depth = h.renderer.read_linear_depth();
  const auto chain = ssao::build_depth_chain(depth, settings.width, settings.height);
  const auto cpu_raw = ssao::reference_ssao(chain, h.renderer.read_view_normals(), h.renderer.ssao_params(),
                                            h.renderer.inverse_far(), estimator, mediump_reference);
  const auto gpu_raw = h.renderer.read_ao_raw();
  ASSERT_EQ(gpu_raw.size(), cpu_raw.size());
  if (estimator == ssao::Estimator::horizon) {
    const Comparison raw = compare(gpu_raw, cpu_raw, 1e-3f);
    EXPECT_EQ(raw.off_by_more, 0u) << what << ", max difference " << raw.max_difference;
  } else {
    const float flip = 1.0f / static_cast<float>(settings.ao_settings.samples) + 1e-3f;
    const Comparison raw = compare(gpu_raw, cpu_raw, 2e-3f);
    EXPECT_LE(raw.max_difference, flip) << what;
    EXPECT_LE(raw.off_by_more, gpu_raw.size() / 100) << what;
  }
  auto low = gpu_raw;
  if (settings.blur.mode != ssao::Blur::off) {
    // The blur, fed the GPU's own raw AO, must match to within half-float rounding of the sums.
    const auto cpu_h = ssao::reference_blur(gpu_raw, h.renderer.blur_params(0), bilateral);
    low = ssao::reference_blur(cpu_h, h.renderer.blur_params(1), bilateral);
    const Comparison blurred = compare(h.renderer.read_ao_blurred(), low, 2e-3f);
    EXPECT_EQ(blurred.off_by_more, 0u) << what << ", max difference " << blurred.max_difference;
    low = h.renderer.read_ao_blurred();
  }
  if (settings.ao_settings.half_resolution) {
    const Comparison upsampled = compare(h.renderer.read_ao_final(), ssao::reference_upsample(low, depth, h.renderer.upsample_params()), 1e-6f);
    EXPECT_EQ(upsampled.off_by_more, 0u) << what << ", max difference " << upsampled.max_difference;
  }
  EXPECT_EQ(h.renderer.gl_error(), "") << what;
}

TEST_P(Pipeline, GpuSsaoAndBlurEqualTheCpuReference) {
  for (const char* scene : {"builtin:demo", "builtin:spheres"}) {
    for (ssao::Pattern pattern : ssao::kPatterns) {
      for (ssao::Blur blur : {ssao::Blur::gaussian, ssao::Blur::bilateral}) {
        render::FrameSettings settings = small_settings();
        settings.ao_settings.pattern = pattern;
        settings.blur.mode = blur;
        Harness h;
        ASSERT_TRUE(h.start(GetParam(), scene, settings));
        expect_gpu_equals_reference(h, std::string(scene) + " " + std::string(ssao::name(pattern)) + " " +
                                           std::string(ssao::name(blur)));
      }
    }
  }
}

// --precision mediump runs the AO_MEDIUMP variant; llvmpipe computes its mediump at 32 bits, so it
// must give what highp gives, within the same tolerances, against the highp CPU reference (the fp16
// error itself is bounded on the CPU: Mediump.VariantStaysWithinTheBoundOfHighp in stress_test.cpp).
TEST_P(Pipeline, EveryEstimatorPrecisionAndResolutionEqualsTheCpuReference) {
  for (ssao::Estimator estimator : ssao::kEstimators)
    for (ssao::Precision precision : ssao::kPrecisions)
    for (bool half : {false, true})
      for (bool chain : {false, true}) {
        render::FrameSettings settings = small_settings();
        settings.ao_settings.precision = precision;
        settings.width = 96;
        settings.height = 72;
        settings.ao_settings.estimator = estimator;
        settings.ao_settings.samples = 16;
        settings.ao_settings.half_resolution = half;
        settings.ao_settings.depth_chain = chain;
        settings.radius = 1.5f;  // large enough that the depth chain's coarse levels are read
        Harness h;
        ASSERT_TRUE(h.start(GetParam(), "builtin:demo", settings));
        const std::string what = std::string(ssao::name(estimator)) + " " + std::string(ssao::name(precision)) +
                                 (half ? " half" : " full") + (chain ? " chain" : " flat");
        // The program that ran is the variant the setting names (on llvmpipe its output cannot tell).
        EXPECT_EQ(h.renderer.targets().ssao_defines.find("#define AO_MEDIUMP") != std::string_view::npos,
                  precision == ssao::Precision::mediump) << what << ": " << h.renderer.targets().ssao_defines;
        EXPECT_EQ(h.renderer.targets().ssao_defines.find("#define ESTIMATOR " + std::to_string(static_cast<int>(estimator))) !=
                      std::string_view::npos, true) << what;
        expect_gpu_equals_reference(h, what);
      }
}

TEST_P(Pipeline, EachEstimatorAndPrecisionIsItsOwnProgram) {
  // play compiles every variant into one Programs up front; each must stay its own program, built
  // with its own #defines, and configure must pick the one the settings name.
  render::FrameSettings settings = small_settings();
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), "builtin:demo", settings));
  std::vector<GLuint> ids;
  std::string error;
  for (ssao::Estimator estimator : ssao::kEstimators)
    for (ssao::Precision precision : ssao::kPrecisions) {
      const std::string what = std::string(ssao::name(estimator)) + " " + std::string(ssao::name(precision));
      const gl::Program* program = h.renderer.programs().ssao(estimator, precision, error);
      ASSERT_NE(program, nullptr) << what << ": " << error;
      EXPECT_EQ(std::count(ids.begin(), ids.end(), program->id()), 0) << what << " shares a program with another variant";
      ids.push_back(program->id());
      const std::string_view defines = h.renderer.programs().ssao_defines(estimator, precision);
      EXPECT_NE(defines.find("#define ESTIMATOR " + std::to_string(static_cast<int>(estimator)) + "\n"), std::string_view::npos) << what;
      EXPECT_EQ(defines.find("#define AO_MEDIUMP") != std::string_view::npos, precision == ssao::Precision::mediump) << what;
      render::FrameSettings variant = settings;
      variant.ao_settings.estimator = estimator;
      variant.ao_settings.precision = precision;
      ASSERT_TRUE(h.renderer.configure(variant, error)) << what << ": " << error;
      EXPECT_EQ(h.renderer.targets().ssao_program, program) << what;
      h.renderer.render(h.camera);
      EXPECT_EQ(h.renderer.gl_error(), "") << what;
    }
}

TEST_P(Pipeline, BackgroundPixelsGetNoOcclusion) {
  for (ssao::Estimator estimator : ssao::kEstimators)
    for (bool half : {false, true}) {
      render::FrameSettings settings = small_settings();
      settings.ao_settings.estimator = estimator;
      settings.ao_settings.half_resolution = half;
      settings.blur.mode = ssao::Blur::gaussian;
      Harness h;
      ASSERT_TRUE(h.start(GetParam(), "builtin:spheres", settings));
      const auto depth = h.renderer.read_linear_depth();
      const auto final_ao = h.renderer.read_ao_final();  // full resolution either way
      const auto raw = h.renderer.read_ao_raw(), blurred = h.renderer.read_ao_blurred();
      size_t background = 0;
      for (size_t i = 0; i < depth.size(); ++i) {
        if (depth[i] > 0.0f) continue;
        ++background;
        EXPECT_EQ(final_ao[i].x, 0.0f) << ssao::name(estimator) << (half ? ", half" : ", full");
        if (!half) {
          EXPECT_EQ(raw[i].x, 0.0f);
          EXPECT_EQ(blurred[i].x, 0.0f);
        }
      }
      EXPECT_GT(background, depth.size() / 10);  // the framing leaves a border of background
    }
}

TEST_P(Pipeline, PlaneFacingTheCameraGetsTheEstimatorsPlaneValue) {
  for (int samples : {8, 16, 32}) {
    render::FrameSettings settings = small_settings();
    settings.ao_settings.estimator = ssao::Estimator::sphere;
    settings.ao_settings.radii = 5;
    settings.ao_settings.samples = samples;
    settings.blur.mode = ssao::Blur::off;
    scene::Framing head_on;
    head_on.azimuth_deg = 0.0;
    head_on.elevation_deg = 0.0;
    head_on.distance = 0.5;  // the plane fills the picture
    Harness h;
    ASSERT_TRUE(h.start(GetParam(), "builtin:plane", settings, head_on));
    const auto& params = h.renderer.ssao_params();
    // On a plane facing the camera a sample is hidden exactly when it lies more than the bias behind
    // the plane; the turn about the view axis leaves that depth unchanged, so every radius agrees.
    int behind = 0;
    for (int i = 0; i < samples; ++i) behind += params.kernel[i].z < -params.radius_4_bias.y ? 1 : 0;
    const float expected = static_cast<float>(behind) / static_cast<float>(samples);
    const auto raw = h.renderer.read_ao_raw();
    const auto depth = h.renderer.read_linear_depth();
    // Away from the border, where no sample leaves the picture.
    for (int y = 12; y < kSide - 12; ++y)
      for (int x = 12; x < kSide - 12; ++x) {
        const size_t i = static_cast<size_t>(y * kSide + x);
        ASSERT_GT(depth[i], 0.0f);
        EXPECT_NEAR(raw[i].x, expected, 1e-3f) << "pixel " << x << "," << y << ", " << samples << " samples";
      }
  }
}

TEST_P(Pipeline, InsideCornerIsDarkerThanAnOpenFace) {
  render::FrameSettings settings = small_settings();
  settings.width = settings.height = 128;
  settings.radius = 0.5f;  // a radius a quarter of the walls' size makes the corner's shadow many pixels wide
  settings.blur.mode = ssao::Blur::off;
  scene::Framing view;
  view.azimuth_deg = 45.0;
  view.elevation_deg = 35.0;
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), "builtin:corner", settings, view));
  const auto ao = h.renderer.read_ao_raw();
  auto ao_near = [&](glm::dvec3 world) {  // mean over 5x5 pixels: the per-pixel turns make single pixels noisy
    const glm::ivec2 p = h.pixel_of(world);
    float sum = 0.0f;
    for (int dy = -2; dy <= 2; ++dy)
      for (int dx = -2; dx <= 2; ++dx) sum += ao[static_cast<size_t>((p.y + dy) * 128 + p.x + dx)].x;
    return sum / 25.0f;
  };
  // On the floor a fifth of the radius from both walls, about three quarters of the sampling sphere
  // lies below the floor or behind a wall; on an open face, one half.
  const float corner = ao_near({0.1, 0.0, 0.1});
  const float floor_open = ao_near({1.5, 0.0, 1.5});
  const float wall_open = ao_near({1.5, 1.5, 0.0});
  EXPECT_GT(corner, floor_open + 0.15f) << "corner " << corner << ", open floor " << floor_open;
  EXPECT_GT(corner, wall_open + 0.15f) << "corner " << corner << ", open wall " << wall_open;
}

TEST_P(Pipeline, NoGlErrorAfterAnyPassInAnyConfiguration) {
  for (bool prepass : {true, false})
    for (bool ao : {true, false})
      for (ssao::Blur blur : {ssao::Blur::off, ssao::Blur::gaussian, ssao::Blur::bilateral})
        for (render::Output view : {render::Output::color, render::Output::ao, render::Output::normal, render::Output::depth}) {
          render::FrameSettings settings = small_settings();
          settings.width = 48;
          settings.height = 32;
          settings.prepass = prepass ? render::Prepass::on : render::Prepass::off;
          settings.ao = ao;
          settings.blur.mode = blur;
          settings.output = view;
          Harness h;
          ASSERT_TRUE(h.start(GetParam(), "builtin:demo", settings));
          EXPECT_EQ(h.renderer.gl_error(), "") << "prepass " << prepass << " ao " << ao << " blur " << ssao::name(blur)
                                               << " view " << render::name(view);
          const render::PassTimes times = h.renderer.collect_times();
          EXPECT_EQ(times.ms[render::kDepthPrepass] >= 0.0, prepass);
          EXPECT_EQ(times.ms[render::kSsao] >= 0.0, ao);
          EXPECT_EQ(times.ms[render::kBlurH] >= 0.0, ao && blur != ssao::Blur::off);
          EXPECT_GE(times.ms[render::kPresent], 0.0);
        }
}

TEST_P(Pipeline, DepthPrepassDoesNotChangeThePicture) {
  render::FrameSettings with = small_settings(), without = small_settings();
  with.prepass = render::Prepass::on;
  without.prepass = render::Prepass::off;
  std::vector<uint8_t> picture;
  {
    Harness a;
    ASSERT_TRUE(a.start(GetParam(), "builtin:demo", with));
    picture = a.renderer.read_color();
  }
  Harness b;
  ASSERT_TRUE(b.start(GetParam(), "builtin:demo", without));
  EXPECT_EQ(picture, b.renderer.read_color());
}

TEST_P(Pipeline, SwitchingOffASavingChangesNoPixel) {
  // aobench measures what each saving saves by turning it off; that is fair only if the saving
  // costs nothing in error: the AO and the picture must be the same either way.
  struct Saving {
    const char* name;
    void (*turn_off)(render::FrameSettings&);
  };
  const Saving savings[] = {
      {"background skip", [](render::FrameSettings& s) { s.ao_settings.skip_background = false; }},
      {"untextured G-buffer variant", [](render::FrameSettings& s) { s.untextured_variant = false; }},
  };
  for (ssao::Estimator estimator : ssao::kEstimators)
    for (const Saving& saving : savings) {
      render::FrameSettings with = small_settings();
      with.ao_settings.estimator = estimator;
      render::FrameSettings without = with;
      saving.turn_off(without);
      const std::string what = std::string(saving.name) + " off, " + std::string(ssao::name(estimator));
      Harness a;
      ASSERT_TRUE(a.start(GetParam(), "builtin:demo", with)) << what;
      Harness b;
      ASSERT_TRUE(b.start(GetParam(), "builtin:demo", without)) << what;
      const auto ao_with = a.renderer.read_ao_final(), ao_without = b.renderer.read_ao_final();
      ASSERT_EQ(ao_with.size(), ao_without.size());
      size_t different = 0;
      for (size_t i = 0; i < ao_with.size(); ++i) different += ao_with[i] != ao_without[i] ? 1 : 0;
      EXPECT_EQ(different, 0u) << what;
      EXPECT_EQ(a.renderer.read_color(), b.renderer.read_color()) << what;
      EXPECT_EQ(b.renderer.gl_error(), "") << what;
    }
}

TEST_P(Pipeline, AutomaticPrepassMeasuresBothAndKeepsTheFaster) {
  render::FrameSettings settings = small_settings();
  settings.prepass = render::Prepass::automatic;
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), "builtin:demo", settings));
  const render::PassTimes first = h.renderer.collect_times();
  EXPECT_GE(first.ms[render::kDepthPrepass], 0.0);  // the first frame tries the prepass
  h.renderer.render(h.camera);
  const render::PassTimes second = h.renderer.collect_times();
  EXPECT_LT(second.ms[render::kDepthPrepass], 0.0);  // the second does without
  ASSERT_GE(h.renderer.raster_ms_with_prepass(), 0.0);
  ASSERT_GE(h.renderer.raster_ms_without_prepass(), 0.0);
  h.renderer.render(h.camera);
  const render::PassTimes third = h.renderer.collect_times();
  const bool keep = h.renderer.raster_ms_with_prepass() <= h.renderer.raster_ms_without_prepass();
  EXPECT_EQ(h.renderer.prepass_in_use(), keep);
  EXPECT_EQ(third.ms[render::kDepthPrepass] >= 0.0, keep);
  EXPECT_EQ(h.renderer.gl_error(), "");
}

TEST_P(Pipeline, SharedSceneWithoutNormalsRendersWithFiniteNormals) {
  render::FrameSettings settings = small_settings();
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), std::string(PLAYER_SHARED_DIR) + "/scenes/teapot-no-normals.glb", settings));
  EXPECT_EQ(h.renderer.gl_error(), "");
  const auto depth = h.renderer.read_linear_depth();
  EXPECT_GT(std::count_if(depth.begin(), depth.end(), [](float d) { return d > 0.0f; }), kSide * kSide / 8);
  for (const glm::vec3& n : h.renderer.read_view_normals()) ASSERT_FALSE(std::isnan(n.x) || std::isnan(n.y) || std::isnan(n.z));
}

TEST_P(Pipeline, BaseColorTextureLandsWhereItsUvsSay) {
  // A square facing the camera with a 2x2 texture: red, green on the top row of the image (v = 0),
  // blue, white below, sampled nearest. glTF puts uv (0, 0) at the image's top-left corner.
  scene::Scene built;
  scene::Material material;
  material.base_color_texture = 0;
  built.materials = {material};
  scene::Texture texture;
  texture.width = texture.height = 2;
  texture.rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
  texture.mag = scene::Filter::nearest;
  texture.mipmaps = false;
  built.textures = {texture};
  scene::Mesh quad = scene::make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0);
  // make_quad's uv runs up the square; flip v so the image's top row is at the top of the square.
  for (scene::Vertex& v : quad.vertices) v.uv.y = 1.0f - v.uv.y;
  scene::add_instance(built, quad);
  scene::update_bounds(built);
  render::FrameSettings settings = small_settings();
  settings.ao = false;
  scene::Framing head_on;
  head_on.azimuth_deg = 0.0;
  head_on.elevation_deg = 0.0;
  head_on.distance = 0.5;
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), std::move(built), settings, head_on));
  const auto color = h.renderer.read_color();  // row 0 at the top
  auto at = [&](int x, int y) { return glm::ivec3(color[static_cast<size_t>((y * kSide + x) * 4)],
                                                  color[static_cast<size_t>((y * kSide + x) * 4 + 1)],
                                                  color[static_cast<size_t>((y * kSide + x) * 4 + 2)]); };
  const glm::ivec3 top_left = at(16, 16), top_right = at(48, 16), bottom_left = at(16, 48), bottom_right = at(48, 48);
  EXPECT_GT(top_left.r, 100);
  EXPECT_LT(top_left.g + top_left.b, 10);
  EXPECT_GT(top_right.g, 100);
  EXPECT_LT(top_right.r + top_right.b, 10);
  EXPECT_GT(bottom_left.b, 100);
  EXPECT_LT(bottom_left.r + bottom_left.g, 10);
  EXPECT_GT(std::min({bottom_right.r, bottom_right.g, bottom_right.b}), 100);
  EXPECT_EQ(h.renderer.gl_error(), "");
}

INSTANTIATE_TEST_SUITE_P(Platforms, Pipeline, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace
