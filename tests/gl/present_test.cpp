// The present pass writes into the platform's framebuffer, frame after frame, with nothing read
// back in between: no frame may depend on what the GPU was still doing for the one before.
#include "app/render_command.h"
#include "harness.h"

namespace {

using test::Harness;

// The defaults, half-resolution AO upsampled inside the present pass, but one frame's AO: temporal
// accumulation makes a frame depend on the ones before it on purpose (TemporalRunsRepeatBitForBit
// checks that it does so the same way every time).
render::FrameSettings settings_for(int width, int height) {
  render::FrameSettings settings;
  settings.width = width;
  settings.height = height;
  settings.check_errors = true;
  settings.temporal = false;
  return settings;
}

scene::Camera camera_at(const Harness& h, double azimuth) {
  scene::Framing framing;
  framing.azimuth_deg = azimuth;
  return scene::frame(h.scene.bounds, framing, h.renderer.settings().width, h.renderer.settings().height);
}

// The surface size is checked once, before any platform is tried: a platform would otherwise
// fail in its own words (EGL_BAD_PARAMETER, an SDL message) or, worse, make a 0x0 surface.
TEST(PlatformSize, AnEmptySurfaceIsRefusedWithTheSizeNamedOnEveryPlatform) {
  for (const std::string& name : platform::names()) {
    for (const platform::Size size : {platform::Size{0, 16}, platform::Size{16, 0}, platform::Size{-1, -1}}) {
      platform::Options options;
      options.name = name;
      options.size = size;
      std::string error;
      EXPECT_EQ(platform::create(options, error), nullptr) << name;
      EXPECT_EQ(error, "--size: " + std::to_string(size.width) + "x" + std::to_string(size.height) +
                           " is not a surface size (expected positive width and height)")
          << name;
    }
  }
  platform::Options smallest;
  smallest.name = "egl";
  smallest.size = {1, 1};
  std::string error;
  EXPECT_NE(platform::create(smallest, error), nullptr) << error;
}

class Surface : public ::testing::TestWithParam<std::string> {};

// GL sets the first viewport to the drawable's size when the context is first made current, so it
// tells the size of the surface the platform really made, not the one it reports.
TEST_P(Surface, IsTheSizeAskedForAndReportsIt) {
  for (const platform::Size size : {platform::Size{64, 48}, platform::Size{48, 64}, platform::Size{1, 97}}) {
    platform::Options options;
    options.name = GetParam();
    options.size = size;
    std::string error;
    const auto session = gl::Session::open(options, error);
    ASSERT_NE(session, nullptr) << error;
    const platform::Platform& surface = session->platform();
    GLint viewport[4] = {};
    gl::api.GetIntegerv(GL_VIEWPORT, viewport);
    EXPECT_EQ(viewport[2], size.width) << GetParam();
    EXPECT_EQ(viewport[3], size.height) << GetParam();
    EXPECT_EQ(surface.size().width, size.width);
    EXPECT_EQ(surface.size().height, size.height);
  }
}

INSTANTIATE_TEST_SUITE_P(Platforms, Surface, ::testing::Values("egl", "osmesa"), test::platform_name);

class Present : public ::testing::TestWithParam<std::string> {};

TEST_P(Present, TwentyFramesOfAStillSceneAreBitIdentical) {
  for (bool reuse : {false, true}) {
    render::FrameSettings settings = settings_for(160, 120);
    settings.reuse_static_ao = reuse;
    Harness h;
    ASSERT_TRUE(h.start(GetParam(), "builtin:demo", settings));
    const std::vector<uint8_t> first = h.renderer.read_color();
    // Frames go out in bursts with no read-back between them, as the player's loop sends them;
    // reading one back waits for the GPU, so only the frame after a burst is compared.
    for (int burst = 0; burst < 5; ++burst) {
      for (int frame = 0; frame < 4; ++frame) h.renderer.render(h.camera);
      EXPECT_EQ(h.renderer.read_color(), first) << "after frame " << 1 + 4 * (burst + 1) << ", reuse-ao " << reuse;
    }
    EXPECT_EQ(h.renderer.gl_error(), "");
  }
}

TEST_P(Present, AFrameOfAnAnimatedRunDoesNotDependOnTheFramesBeforeIt) {
  const render::FrameSettings settings = settings_for(160, 120);
  constexpr int kFrame = 12;
  auto azimuth = [](int frame) { return 20.0 + 7.0 * frame; };
  Harness run;
  ASSERT_TRUE(run.start(GetParam(), "builtin:demo", settings));
  for (int frame = 1; frame <= kFrame; ++frame) run.renderer.render(camera_at(run, azimuth(frame)));
  const std::vector<uint8_t> after_run = run.renderer.read_color();
  // The same frame, reached by another path: straight after the first frame, and after frames
  // that went the other way round.
  Harness direct;
  ASSERT_TRUE(direct.start(GetParam(), "builtin:demo", settings));
  direct.renderer.render(camera_at(direct, azimuth(kFrame)));
  EXPECT_EQ(direct.renderer.read_color(), after_run);
  for (int frame = 2 * kFrame; frame > kFrame; --frame) direct.renderer.render(camera_at(direct, azimuth(frame)));
  direct.renderer.render(camera_at(direct, azimuth(kFrame)));
  EXPECT_EQ(direct.renderer.read_color(), after_run);
  EXPECT_EQ(run.renderer.gl_error(), "");
  EXPECT_EQ(direct.renderer.gl_error(), "");
}

// With temporal accumulation a frame is the average of the ones before it: the same frames must
// give the same average whether they went out in bursts or were each read back (waiting for the GPU)
// before the next, over a turn of the camera and then a still stretch that fills the history.
TEST_P(Present, TemporalRunsRepeatBitForBit) {
  render::FrameSettings settings = settings_for(160, 120);
  settings.temporal = true;
  settings.history = 8;
  auto run = [&](bool read_each) {
    Harness h;
    EXPECT_TRUE(h.start(GetParam(), "builtin:demo", settings));
    for (int frame = 1; frame <= 16; ++frame) {
      h.renderer.render(camera_at(h, 20.0 + 3.0 * std::min(frame, 8)));
      if (read_each) (void)h.renderer.read_color();
    }
    EXPECT_EQ(h.renderer.gl_error(), "");
    EXPECT_EQ(h.renderer.ao_frames_averaged(), 8);
    return h.renderer.read_color();
  };
  const std::vector<uint8_t> bursts = run(false);
  EXPECT_EQ(run(true), bursts);
  EXPECT_EQ(run(false), bursts);
}

// --ao-strength powers 1 - AO in the shaded image only: 0 shows the image without AO, 2 darkens
// every occluded pixel further, and the AO itself (what accuracy is measured on) stays as computed.
TEST_P(Present, AoStrengthChangesTheShadedImageButNotTheAo) {
  auto frame_with = [&](float strength, bool ao, std::vector<glm::vec2>* ao_out) {
    render::FrameSettings settings = settings_for(96, 72);
    settings.ao_strength = strength;
    settings.ao = ao;
    Harness h;
    EXPECT_TRUE(h.start(GetParam(), "builtin:demo", settings));
    if (ao_out != nullptr) *ao_out = h.renderer.read_ao_final();
    return h.renderer.read_color();
  };
  std::vector<glm::vec2> ao_one, ao_two;
  const std::vector<uint8_t> one = frame_with(1.0f, true, &ao_one);
  const std::vector<uint8_t> two = frame_with(2.0f, true, &ao_two);
  EXPECT_EQ(frame_with(0.0f, true, nullptr), frame_with(1.0f, false, nullptr));
  EXPECT_EQ(ao_one, ao_two);
  size_t darker = 0, occluded = 0;
  for (size_t i = 0; i < one.size(); i += 4) {
    const size_t pixel = i / 4;
    const size_t x = pixel % 96, y = 71 - pixel / 96;  // AO rows are bottom-up
    // Where AO is under 1%, squaring 1 - AO darkens by under two thirds of a step, and the GPU's pow()
    // and sRGB encoding round it either way (llvmpipe: 148 against 147 at AO 0.00024).
    if (ao_one[y * 96 + x].x < 0.01f)
      EXPECT_LE(std::abs(two[i + 1] - one[i + 1]), 1) << i;
    else
      EXPECT_LE(two[i + 1], one[i + 1]) << i;
    if (one[i + 1] < 40) continue;  // too dark to tell a step apart
    if (ao_one[y * 96 + x].x < 0.1f) continue;
    ++occluded;
    darker += two[i + 1] < one[i + 1] ? 1 : 0;
  }
  EXPECT_GT(occluded, 50u);
  EXPECT_GT(darker, occluded * 9 / 10);
}

TEST_P(Present, FadeDarkensTheWholeImage) {
  render::FrameSettings settings = settings_for(64, 48);
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), "builtin:demo", settings));
  const std::vector<uint8_t> full = h.renderer.read_color();
  h.renderer.render(render::view_of(h.camera), 0.0f);
  const std::vector<uint8_t> black = h.renderer.read_color();
  for (size_t i = 0; i < black.size(); i += 4) {
    ASSERT_EQ(black[i], 0) << i;
    ASSERT_EQ(black[i + 3], 255) << i;
  }
  h.renderer.render(render::view_of(h.camera), 0.5f);
  const std::vector<uint8_t> half = h.renderer.read_color();
  size_t darker = 0, lit = 0;
  for (size_t i = 0; i < half.size(); i += 4) {
    if (full[i + 1] < 8) continue;
    ++lit;
    darker += half[i + 1] < full[i + 1] ? 1 : 0;
  }
  EXPECT_GT(lit, 0u);
  EXPECT_EQ(darker, lit);
}

// The present pass shades only the bands of the view whose tiles hold a surface and fills the rest
// with the background (FrameSettings::present_tiles): the picture is the one shading every pixel
// gives, byte for byte, in every output, at sizes that are no multiple of the 16-pixel tiles or the
// 128-pixel bands, with the scene framed, small, filling the view, at its edge and out of it.
TEST_P(Present, ShadingOnlyTheBandsWithSurfacesLeavesThePictureAsItWas) {
  struct Case {
    const char* what;
    int width, height;
    double distance;
    double sideways;  // the camera's target moved to its right, in multiples of its distance
  };
  for (const Case c : {Case{"framed", 150, 97, 1.0, 0.0}, Case{"small", 200, 300, 6.0, 0.0}, Case{"filling", 131, 77, 0.35, 0.0},
                       Case{"at the edge", 170, 140, 1.0, 0.45}, Case{"out of view", 90, 60, 1.0, -4.0}}) {
    for (const render::Picture output :
         {render::Picture::color, render::Picture::ao, render::Picture::normal, render::Picture::depth}) {
      auto picture = [&](bool bands) {
        render::FrameSettings settings = settings_for(c.width, c.height);
        settings.present_tiles = bands;
        settings.output = output;
        scene::Framing framing;
        framing.distance = c.distance;
        Harness h;
        EXPECT_TRUE(h.start(GetParam(), "builtin:demo", settings, framing));
        scene::Camera camera = h.camera;
        const glm::dvec3 forward = camera.target - camera.eye;
        camera.target += glm::normalize(glm::cross(forward, camera.up)) * (c.sideways * glm::length(forward));
        h.renderer.render(camera);
        EXPECT_EQ(h.renderer.gl_error(), "");
        return h.renderer.read_color();
      };
      const std::vector<uint8_t> shaded_everywhere = picture(false), shaded_in_bands = picture(true);
      size_t background = 0;
      for (size_t i = 0; i + 3 < shaded_everywhere.size(); i += 4)
        background += shaded_everywhere[i] == shaded_everywhere[0] && shaded_everywhere[i + 1] == shaded_everywhere[1] ? 1 : 0;
      EXPECT_EQ(shaded_in_bands, shaded_everywhere) << c.what << ", " << render::name(output) << ", " << background
                                                    << " background pixels of " << shaded_everywhere.size() / 4;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Platforms, Present, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace

// Scenes load knowing the context's largest texture: one this GPU cannot hold is drawn white with a
// warning rather than failing the item at upload (play's loader and render take it from here).
TEST(LoadOptions, FollowTheContextsLargestTexture) {
  gl::Caps caps;
  caps.max_texture_size = 2048;
  EXPECT_EQ(app::load_options_for(caps).max_texture_size, 2048);
  caps.max_texture_size = 65536;  // beyond the loader's own limit, which stays
  EXPECT_EQ(app::load_options_for(caps).max_texture_size, scene::LoadOptions{}.max_texture_size);
}
