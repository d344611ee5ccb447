// One session per context: programs compiled once and shared; one Output interface for a view and a
// light field display, with the estimator fallback in the light field output alone.
#include "harness.h"
#include "lightfield/display_file.h"
#include "render/light_field.h"
#include "render/output.h"

#include <gtest/gtest.h>

namespace {

class Session : public test::SessionTest {
 protected:
  void SetUp() override {
    test::SessionTest::SetUp();
    if (HasFatalFailure()) return;
    std::string error;
    std::ostringstream log;
    ASSERT_TRUE(scene::load("builtin:demo", scene_, error, log)) << error;
  }
  render::PresentTarget surface() const {
    return {session_->platform().framebuffer(), 0, 0, session_->platform().srgb_framebuffer()};
  }
  render::FrameSettings settings() const {
    render::FrameSettings s;
    s.width = 64;
    s.height = 48;
    s.check_errors = true;
    return s;
  }

  scene::Scene scene_;
};

// A second renderer in the same context (play's drawer beside a self-check, two tests' fixtures)
// finds every program compiled, and draws the same picture with them.
TEST_P(Session, CompilesEachProgramOncePerContext) {
  std::string error;
  std::vector<uint8_t> first_image;
  size_t after_first = 0;
  {
    render::Renderer first;
    ASSERT_TRUE(first.init(*session_, surface(), error) && first.upload(scene_, error) && first.configure(settings(), error))
        << error;
    after_first = session_->programs().compiled();
    EXPECT_GT(after_first, 8u);  // G-buffer, depth, the AO passes, present: each its own program
    first.render(scene::frame(scene_.bounds, {}, 64, 48));
    ASSERT_EQ(first.gl_error(), "");
    first_image = first.read_color();
  }
  render::Renderer second;  // the first one's GL objects are gone; the session's programs are not
  ASSERT_TRUE(second.init(*session_, surface(), error) && second.upload(scene_, error) && second.configure(settings(), error))
      << error;
  EXPECT_EQ(session_->programs().compiled(), after_first);
  second.render(scene::frame(scene_.bounds, {}, 64, 48));
  ASSERT_EQ(second.gl_error(), "");
  EXPECT_EQ(second.read_color(), first_image);
}

// A variant that does not compile is reported each time it is asked for, and takes no slot.
TEST_P(Session, AProgramThatFailsIsReportedEachTimeAndNotKept) {
  gl::ProgramCache& cache = session_->programs();
  const size_t before = cache.compiled();
  for (int attempt = 0; attempt < 2; ++attempt) {
    std::string error;
    EXPECT_EQ(cache.get({{GL_COMPUTE_SHADER, "ssao.comp"}}, "#error a variant that cannot compile\n", error), nullptr);
    EXPECT_NE(error.find("gles_shaders/ssao.comp (variant: #error a variant that cannot compile"), std::string::npos) << error;
    EXPECT_EQ(cache.compiled(), before);
  }
  std::string error;
  EXPECT_EQ(cache.get({{GL_COMPUTE_SHADER, "no_such_file.comp"}}, "", error), nullptr);
  EXPECT_EQ(error, "gles_shaders/no_such_file.comp: no such embedded shader");
}

// Optical modules run Algorithm 2, which horizon has no form of: the light field output falls back
// to hemisphere and says so; a quilt's views are ordinary cameras and keep horizon; a view output
// never changes the estimator.
TEST_P(Session, OnlyTheModulesOutputFallsBackFromHorizon) {
  render::FrameSettings horizon = settings();
  horizon.ao_settings.estimator = ssao::Estimator::horizon;
  std::string error;
  lightfield::Display modules;
  ASSERT_TRUE(lightfield::load_display(PLAYER_BOARD_DIR "/displays/desk-8.toml", modules, error)) << error;
  render::LightFieldRenderer light_field;
  ASSERT_TRUE(light_field.init(*session_, error) && light_field.upload(scene_, error)) << error;
  ASSERT_TRUE(light_field.configure(modules, horizon, scene::frame(scene_.bounds, {}, 64, 48), error)) << error;
  EXPECT_EQ(light_field.output().targets().settings().ao_settings.estimator, ssao::Estimator::hemisphere);
  EXPECT_EQ(light_field.output().adjustment().rfind("estimator: hemisphere (horizon", 0), 0u)
      << light_field.output().adjustment();
  light_field.render();
  EXPECT_EQ(light_field.gl_error(), "");

  render::Renderer view;
  ASSERT_TRUE(view.init(*session_, surface(), error) && view.upload(scene_, error) && view.configure(horizon, error)) << error;
  EXPECT_EQ(view.settings().ao_settings.estimator, ssao::Estimator::horizon);

  lightfield::Display quilt;
  ASSERT_TRUE(lightfield::load_display(PLAYER_BOARD_DIR "/displays/looking-glass-portrait.toml", quilt, error)) << error;
  ASSERT_TRUE(light_field.configure(quilt, horizon, scene::frame(scene_.bounds, {}, 64, 48), error)) << error;
  EXPECT_EQ(light_field.output().targets().settings().ao_settings.estimator, ssao::Estimator::horizon);
  EXPECT_EQ(light_field.output().adjustment(), "");
}

// The same frame drawn through the interface as `play` draws it (configure, aim, render, present)
// and through the Renderer of `render` is the same picture.
TEST_P(Session, ViewOutputDrawsWhatTheRendererDraws) {
  std::string error;
  render::Renderer renderer;
  ASSERT_TRUE(renderer.init(*session_, surface(), error) && renderer.upload(scene_, error) &&
              renderer.configure(settings(), error))
      << error;
  const scene::Camera camera = scene::frame(scene_.bounds, {}, 64, 48);
  renderer.render(camera);
  const std::vector<uint8_t> expected = renderer.read_color();

  render::Programs programs;
  ASSERT_TRUE(programs.build(*session_, error)) << error;
  render::SceneGpu gpu;
  ASSERT_TRUE(gpu.upload(scene_, session_->caps(), error)) << error;
  render::ViewOutput view(programs, session_->caps());
  render::Output& output = view;
  ASSERT_TRUE(output.configure(settings(), gpu, surface().srgb, error)) << error;
  EXPECT_EQ(output.view_size(), glm::ivec2(64, 48));
  output.aim(camera);
  std::string gl_error;
  const render::OutputFrame frame{gpu, 1.0f, nullptr, &gl_error};
  output.render(frame);
  output.present(frame, surface(), 64, 48);
  EXPECT_EQ(gl_error, "");
  EXPECT_EQ(render::read_presented(surface(), 64, 48), expected);
}

INSTANTIATE_TEST_SUITE_P(Platforms, Session, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace
