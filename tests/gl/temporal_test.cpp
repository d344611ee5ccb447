// Temporal accumulation: a still camera averages its frames exactly as the CPU reference averages
// the same frames; a surface that was hidden in the previous frame starts a new history instead of
// inheriting what stood in front of it; a moving camera keeps the history of surfaces that stay in
// view, but no more than TEMPORAL_MOVING_FRAMES of it.
#include "harness.h"
#include "render/readback.h"
#include "scene/procedural.h"
#include "ssao/reference.h"

#include <cmath>

namespace {

using test::Harness;

class Temporal : public ::testing::TestWithParam<std::string> {};

render::FrameSettings temporal_settings(int side) {
  render::FrameSettings settings;  // the default estimator, at full resolution so texels are pixels
  settings.width = settings.height = side;
  settings.check_errors = true;
  settings.ao_settings.half_resolution = false;
  settings.blur.mode = ssao::Blur::off;
  settings.temporal = true;
  return settings;
}

std::vector<ssao::AoTexel> cpu_frame(const Harness& h) {
  const render::FrameSettings& settings = h.renderer.settings();
  const auto chain = ssao::build_depth_chain(h.renderer.read_linear_depth(), settings.width, settings.height);
  return ssao::reference_ssao(chain, h.renderer.read_view_normals(), h.renderer.read_view_face_normals(),
                              h.renderer.ssao_params(), h.renderer.inverse_far(), settings.ao_settings.estimator);
}

double mean_abs(const std::vector<glm::vec2>& a, const std::vector<glm::vec2>& b, float* worst = nullptr) {
  double sum = 0.0;
  size_t n = 0;
  float max_difference = 0.0f;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].y <= 0.0f || b[i].y <= 0.0f) continue;
    const float d = std::abs(a[i].x - b[i].x);
    sum += d;
    max_difference = std::max(max_difference, d);
    ++n;
  }
  if (worst != nullptr) *worst = max_difference;
  return n > 0 ? sum / static_cast<double>(n) : 0.0;
}

// 64 frames of a still camera: each frame turns its samples anew, and the GPU's running average
// must be the CPU reference's average of the same 64 frames (the reference computes each frame
// from the very block the GPU used). The bound is the rgba16f history's rounding, once per frame.
// The single frame's distance from that average is the noise accumulation removes.
TEST_P(Temporal, AStillCameraConvergesOnTheAverageOfItsFrames) {
  constexpr int kFrames = 64;
  render::FrameSettings settings = temporal_settings(64);
  settings.history = kFrames;
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), "builtin:demo", settings));
  const std::vector<glm::vec2> first_frame = h.renderer.read_ao_raw();
  std::vector<ssao::AoTexel> cpu_average = cpu_frame(h);
  for (int frame = 2; frame <= kFrames; ++frame) {
    h.renderer.render(h.camera);
    ASSERT_FALSE(h.renderer.reused_ao()) << "frame " << frame;
    const std::vector<ssao::AoTexel> cpu = cpu_frame(h);
    for (size_t i = 0; i < cpu.size(); ++i) cpu_average[i].x += (cpu[i].x - cpu_average[i].x) / static_cast<float>(frame);
  }
  EXPECT_EQ(h.renderer.ao_frames_averaged(), kFrames);
  const std::vector<glm::vec2> gpu_average = h.renderer.read_ao_blurred();
  float worst = 0.0f;
  const double error = mean_abs(gpu_average, cpu_average, &worst);
  const double noise = mean_abs(first_frame, cpu_average);
  EXPECT_LE(error, 5e-4) << "worst " << worst;
  EXPECT_LE(worst, 4e-3);
  EXPECT_GE(noise, 10.0 * error) << "one frame's distance from the average of 64";
  for (float frames : h.renderer.read_history_frames()) ASSERT_TRUE(frames == 0.0f || frames == kFrames);
  // The history is full: the next frame keeps it rather than computing AO again.
  h.renderer.render(h.camera);
  EXPECT_TRUE(h.renderer.reused_ao());
  EXPECT_EQ(h.renderer.read_ao_blurred(), gpu_average);
  EXPECT_EQ(h.renderer.gl_error(), "");
}

scene::Scene floor_with_box(float box_x) {
  scene::Scene scene;
  scene.name = "floor with box";
  scene.materials.resize(1);
  scene::add_instance(scene, scene::make_box({-3, -0.2f, -3}, {3, 0, 3}, 0));
  scene::add_instance(scene, scene::make_box({box_x - 0.9f, 0, -0.9f}, {box_x + 0.9f, 1.6f, 0.9f}, 0));
  scene::update_bounds(scene);
  return scene;
}

// The box moves away between two frames of a still camera: the floor it uncovers had no history
// of its own (its history texels were the box's front, nearer by far), so it must start anew, with
// exactly this frame's AO and a count of 1: no ghost of the box. The floor that was visible
// throughout keeps its history.
TEST_P(Temporal, AnUncoveredFloorShowsNoGhostOfTheBoxThatHidItLast) {
  render::FrameSettings settings = temporal_settings(96);
  settings.history = 16;
  settings.reuse_static_ao = false;  // the scene changes under a still camera: the player's never do
  scene::Framing framing;
  framing.elevation_deg = 20.0;
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), floor_with_box(-1.3f), settings, framing));
  for (int frame = 0; frame < 8; ++frame) h.renderer.render(h.camera);
  const std::vector<float> depth_before = h.renderer.read_linear_depth();
  std::string error;
  ASSERT_TRUE(h.renderer.upload(floor_with_box(1.3f), error)) << error;
  h.renderer.render(h.camera);
  const std::vector<float> depth_after = h.renderer.read_linear_depth();
  const std::vector<float> frames = h.renderer.read_history_frames();
  const std::vector<glm::vec2> raw = h.renderer.read_ao_raw();
  const std::vector<glm::vec2> average = h.renderer.read_ao_blurred();
  size_t uncovered = 0, unchanged = 0, kept = 0;
  for (size_t i = 0; i < depth_after.size(); ++i) {
    if (depth_after[i] <= 0.0f || depth_before[i] <= 0.0f) continue;
    const float change = std::abs(depth_after[i] - depth_before[i]) / depth_after[i];
    if (depth_after[i] > depth_before[i] * 1.05f) {  // was the box, is the floor now
      ++uncovered;
      EXPECT_EQ(frames[i], 1.0f) << "texel " << i << " raw depth " << raw[i].y / h.renderer.inverse_far() << " after "
                                 << depth_after[i] << " before " << depth_before[i] << " avg g "
                                 << average[i].y / h.renderer.inverse_far();
      EXPECT_EQ(average[i].x, raw[i].x) << "texel " << i;
    } else if (change < 1e-4f) {
      ++unchanged;
      kept += frames[i] == 10.0f ? 1 : 0;  // 8 + the first frame + this one
    }
  }
  EXPECT_GT(uncovered, 150u);
  EXPECT_GT(kept, unchanged * 95 / 100) << "of " << unchanged;
  EXPECT_EQ(h.renderer.gl_error(), "");
}

// The floor rises between two frames of a still camera: each pixel's history texel is the old floor,
// whose normal is the new one's, so only the depth test can tell it is another surface (the box
// above is told apart by its normals too). Every floor pixel must start anew.
TEST_P(Temporal, ARaisedFloorStartsAnewOnDepthAlone) {
  render::FrameSettings settings = temporal_settings(64);
  settings.history = 16;
  settings.reuse_static_ao = false;  // the scene changes under a still camera: the player's never do
  const auto floor_at = [](float top) {
    scene::Scene scene;
    scene.name = "floor";
    scene.materials.resize(1);
    scene::add_instance(scene, scene::make_box({-3, top - 0.2f, -3}, {3, top, 3}, 0));
    scene::update_bounds(scene);
    return scene;
  };
  scene::Framing framing;
  framing.elevation_deg = 30.0;
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), floor_at(0.0f), settings, framing));
  for (int frame = 0; frame < 4; ++frame) h.renderer.render(h.camera);
  const std::vector<float> depth_before = h.renderer.read_linear_depth();
  std::string error;
  ASSERT_TRUE(h.renderer.upload(floor_at(0.5f), error)) << error;
  h.renderer.render(h.camera);
  const std::vector<float> depth_after = h.renderer.read_linear_depth();
  const std::vector<float> frames = h.renderer.read_history_frames();
  size_t moved = 0;
  for (size_t i = 0; i < depth_after.size(); ++i) {
    // 5%: beyond the history's depth tolerance (3%) by a margin.
    if (depth_after[i] <= 0.0f || depth_before[i] <= 0.0f || depth_after[i] > depth_before[i] * 0.95f) continue;
    ++moved;
    EXPECT_EQ(frames[i], 1.0f) << "texel " << i << " depth " << depth_before[i] << " -> " << depth_after[i];
  }
  EXPECT_GT(moved, 500u) << "of " << depth_after.size();
  EXPECT_EQ(h.renderer.gl_error(), "");
}

// A turntable: every surface that stays in view keeps its history through the reprojection, but
// never more than TEMPORAL_MOVING_FRAMES of it while the camera moves; it converges on a still camera.
TEST_P(Temporal, AMovingCameraKeepsAtMostTheMovingHistory) {
  render::FrameSettings settings = temporal_settings(96);
  settings.history = 32;
  settings.reuse_static_ao = false;
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), "builtin:spheres", settings));
  auto camera_at = [&](double azimuth) {
    scene::Framing framing;
    framing.azimuth_deg = azimuth;
    return scene::frame(h.scene.bounds, framing, settings.width, settings.height);
  };
  for (int frame = 1; frame <= 12; ++frame) h.renderer.render(camera_at(30.0 + 0.5 * frame));
  std::vector<float> frames = h.renderer.read_history_frames();
  size_t surface = 0, at_limit = 0, over = 0;
  for (float f : frames) {
    if (f <= 0.0f) continue;
    ++surface;
    at_limit += f == TEMPORAL_MOVING_FRAMES ? 1 : 0;
    over += f > TEMPORAL_MOVING_FRAMES ? 1 : 0;
  }
  EXPECT_EQ(over, 0u);
  EXPECT_GT(at_limit, surface * 9 / 10) << "of " << surface << " surface texels";
  for (int frame = 0; frame < 40; ++frame) h.renderer.render(camera_at(36.0));
  frames = h.renderer.read_history_frames();
  for (float f : frames) ASSERT_TRUE(f == 0.0f || f == 32.0f) << f;
  EXPECT_EQ(h.renderer.ao_frames_averaged(), 32);
  EXPECT_EQ(h.renderer.gl_error(), "");
}

// A cut (a new item, a jump of the camera path) starts every history again.
TEST_P(Temporal, ResettingTheHistoryStartsEveryTexelAnew) {
  render::FrameSettings settings = temporal_settings(64);
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), "builtin:demo", settings));
  for (int frame = 0; frame < 5; ++frame) h.renderer.render(h.camera);
  h.renderer.targets().reset_history();
  h.renderer.render(h.camera);
  for (float f : h.renderer.read_history_frames()) ASSERT_TRUE(f == 0.0f || f == 1.0f) << f;
  EXPECT_EQ(h.renderer.read_ao_blurred(), h.renderer.read_ao_raw());
  EXPECT_EQ(h.renderer.ao_frames_averaged(), 1);
}

INSTANTIATE_TEST_SUITE_P(Platforms, Temporal, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace
