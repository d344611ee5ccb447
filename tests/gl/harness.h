#pragma once
// A context, a renderer and a framed scene, for GL tests on either platform.
#include "gl/caps.h"
#include "gl/gl_api.h"
#include "gl/session.h"
#include "platform/platform.h"
#include "render/renderer.h"
#include "scene/load.h"

#include <gtest/gtest.h>

#include <memory>
#include <sstream>

namespace test {

// A context for a GL test on `platform_name` with a surface of `width` x `height`, KHR_debug on.
inline std::unique_ptr<gl::Session> open_session(const std::string& platform_name, int width, int height, std::string& error) {
  platform::Options options;
  options.name = platform_name;
  options.size = {width, height};
  options.debug_context = true;
  return gl::Session::open(options, error);
}

// A test run on each platform (its parameter) with a 64x48 session open.
class SessionTest : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    std::string error;
    session_ = open_session(GetParam(), 64, 48, error);
    ASSERT_TRUE(session_) << error;
  }
  std::unique_ptr<gl::Session> session_;
};

struct Harness {
  std::unique_ptr<gl::Session> session;  // first: everything below goes before its context
  platform::Platform* platform = nullptr;
  gl::Caps caps;
  render::Renderer renderer;
  scene::Scene scene;
  scene::Camera camera;

  // Creates the context, loads `scene_spec` and renders one frame with `settings` from `framing`.
  ::testing::AssertionResult start(const std::string& platform_name, const std::string& scene_spec,
                                   const render::FrameSettings& settings, const scene::Framing& framing = {}) {
    std::string error;
    if (!open(platform_name, settings, error)) return ::testing::AssertionFailure() << error;
    std::ostringstream log;
    if (!scene::load(scene_spec, scene, error, log)) return ::testing::AssertionFailure() << error;
    return render_first_frame(settings, framing);
  }

  // The same for a scene built by the test.
  ::testing::AssertionResult start(const std::string& platform_name, scene::Scene built, const render::FrameSettings& settings,
                                   const scene::Framing& framing = {}) {
    std::string error;
    if (!open(platform_name, settings, error)) return ::testing::AssertionFailure() << error;
    scene = std::move(built);
    return render_first_frame(settings, framing);
  }

  // A context whose surface is the size of the frames.
  bool open(const std::string& platform_name, const render::FrameSettings& settings, std::string& error) {
    session = open_session(platform_name, settings.width, settings.height, error);
    if (!session) return false;
    platform = &session->platform();
    caps = session->caps();
    return true;
  }

  render::PresentTarget target() const { return {platform->framebuffer(), 0, 0, platform->srgb_framebuffer()}; }

  ::testing::AssertionResult render_first_frame(const render::FrameSettings& settings, const scene::Framing& framing) {
    std::string error;
    if (!renderer.init(*session, target(), error) || !renderer.upload(scene, error) || !renderer.configure(settings, error))
      return ::testing::AssertionFailure() << error;
    camera = scene::frame(scene.bounds, framing, settings.width, settings.height);
    renderer.render(camera);
    return ::testing::AssertionSuccess();
  }

  // The pixel (GL order, row 0 at the bottom) where a world point lands.
  glm::ivec2 pixel_of(const glm::dvec3& world) const {
    const glm::dvec4 clip = camera.projection() * camera.view() * glm::dvec4(world, 1.0);
    const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
    const auto& s = renderer.settings();
    return glm::ivec2(static_cast<int>((ndc.x * 0.5 + 0.5) * s.width), static_cast<int>((ndc.y * 0.5 + 0.5) * s.height));
  }
};

inline std::string platform_name(const ::testing::TestParamInfo<std::string>& info) {
  return info.param;
}

}  // namespace test
