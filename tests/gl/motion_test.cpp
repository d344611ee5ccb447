// Temporal AO in an animated scene: the G-buffer's motion target holds, at each pixel, how far its
// surface point moved since the previous pose (a node's move, a skin's bend, a morph's reshape, each
// computed here on the CPU), still surfaces hold none, and the temporal pass follows it: a part
// moving towards the camera keeps its own history, which the camera's reprojection alone loses.
#include <glm/gtc/matrix_transform.hpp>
#include "animated_scenes.h"
#include "harness.h"
#include "render/readback.h"
#include "scene/animation.h"
#include "scene/procedural.h"

namespace {

using test::Harness;

constexpr int kSize = test::kAnimatedSize;

render::FrameSettings motion_frame() {
  render::FrameSettings settings = test::small_animated_frame();
  settings.ao_settings.half_resolution = false;  // AO texels are pixels
  settings.reuse_static_ao = false;
  return settings;
}

scene::Framing from_the_front() {
  return test::from_the_front(30.0);
}

// A white floor and a red box of `box` on it, carried by node 0 of `rig`.
scene::Scene floor_and(scene::Mesh box, std::shared_ptr<scene::Rig> rig) {
  scene::Scene built;
  scene::Material white, red;
  red.base_color = glm::vec4(1, 0, 0, 1);
  built.materials = {white, red};
  scene::add_instance(built, scene::make_quad({-3, 0, 3}, {6, 0, 0}, {0, 0, -6}, 0));
  scene::add_instance(built, std::move(box));
  built.instances[1].node = 0;
  built.rig = std::move(rig);
  scene::update_bounds(built);
  built.bounds.min = glm::dvec3(-3, 0, -3);  // the floor, and every pose of the box above it
  built.bounds.max = glm::dvec3(3, 2, 3);
  return built;
}

std::shared_ptr<scene::Rig> sliding_rig(glm::vec3 from, glm::vec3 to, float seconds) {
  auto rig = std::make_shared<scene::Rig>();
  rig->nodes.resize(1);
  rig->nodes[0].translation = from;
  scene::AnimationChannel slide;
  slide.node = 0;
  slide.property = scene::AnimatedProperty::translation;
  slide.times = {0.0f, seconds};
  slide.values = {glm::vec4(from, 0.0f), glm::vec4(to, 0.0f)};
  rig->animations.push_back({"slide", {slide}, seconds});
  return rig;
}

// Poses at `before`, renders, poses at `now`, renders.
void render_two_poses(Harness& h, double before, double now) {
  scene::Pose pose(h.renderer.scene().rig());
  pose.at(scene::Rig::kAllAnimations, before);
  h.renderer.pose(pose);
  h.renderer.render(h.camera);
  pose.at(scene::Rig::kAllAnimations, now);
  h.renderer.pose(pose);
  h.renderer.render(h.camera);
}

glm::vec3 motion_at(const Harness& h, const std::vector<glm::vec3>& motion, glm::dvec3 world) {
  const glm::ivec2 p = h.pixel_of(world);
  return motion[static_cast<size_t>(p.y * kSize + p.x)];
}

// The world point a pixel shows (the G-buffer's depth, unprojected).
glm::dvec3 world_at(const Harness& h, glm::dvec3 world) {
  const render::WorldSurface surface = render::read_world_surface(h.renderer.targets(), render::view_of(h.camera));
  const glm::ivec2 p = h.pixel_of(world);
  const size_t i = static_cast<size_t>(p.y * kSize + p.x) * 4;
  EXPECT_EQ(surface.position[i + 3], 1.0f) << "the pixel shows the background";
  return {surface.position[i], surface.position[i + 1], surface.position[i + 2]};
}

// The motion a world displacement `previous - now` is, in the camera's view space.
glm::vec3 in_view(const Harness& h, glm::dvec3 displacement) {
  return glm::vec3(glm::dmat3(h.camera.view()) * displacement);
}

void expect_near(glm::vec3 actual, glm::vec3 expected, float tolerance, const char* what) {
  EXPECT_LE(glm::length(actual - expected), tolerance)
      << what << ": motion (" << actual.x << ", " << actual.y << ", " << actual.z << "), expected (" << expected.x << ", "
      << expected.y << ", " << expected.z << ")";
}

class Motion : public ::testing::TestWithParam<std::string> {};

TEST_P(Motion, ANodesMoveIsItsPixelsMotionAndTheFloorHasNone) {
  Harness h;
  ASSERT_TRUE(
      h.start(GetParam(),
              floor_and(scene::make_box({-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f}, 1), sliding_rig({-1, 0, 0}, {1, 0, 0}, 2.0f)),
              motion_frame(), from_the_front()));
  ASSERT_TRUE(h.renderer.targets().motion_attached()) << "an animated scene's G-buffer has a motion target";
  render_two_poses(h, 1.0, 1.1);  // x from 0 to 0.1
  EXPECT_EQ(h.renderer.gl_error(), "");
  const std::vector<glm::vec3> motion = render::read_motion(h.renderer.targets());
  ASSERT_EQ(motion.size(), static_cast<size_t>(kSize * kSize));
  const glm::vec3 expected = in_view(h, {-0.1, 0, 0});
  expect_near(motion_at(h, motion, {0.1, 1.0, 0.0}), expected, 1e-3f, "the box's top");
  expect_near(motion_at(h, motion, {0.1, 0.5, 0.5}), expected, 1e-3f, "the box's front");
  EXPECT_EQ(motion_at(h, motion, {2.0, 0.0, 2.0}), glm::vec3(0.0f)) << "the floor did not move";
  // Every pixel is either the box's move or none.
  int box = 0;
  for (const glm::vec3& m : motion) {
    if (m == glm::vec3(0.0f)) continue;
    EXPECT_LE(glm::length(m - expected), 1e-3f);
    ++box;
  }
  EXPECT_GT(box, 100);
  // Posed again where it is: the next frame has no motion.
  render_two_poses(h, 1.1, 1.1);
  for (const glm::vec3& m : render::read_motion(h.renderer.targets())) ASSERT_EQ(m, glm::vec3(0.0f));
}

// The top half of a box follows joint 1, which the animation tilts about +Z: the top's motion is
// the CPU's skinning of the point at the previous pose less at this one.
TEST_P(Motion, ASkinsBendIsItsPixelsMotion) {
  const std::shared_ptr<scene::Rig> rig = test::tilting_rig();
  scene::Scene built = floor_and(test::jointed_box(), rig);
  built.instances[1].skin = 0;
  scene::Pose rest(rig);
  scene::skin_matrices(rig->skins[0], rest.worlds(), built.instances[1].skin_matrices);
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), std::move(built), motion_frame(), from_the_front()));
  render_two_poses(h, 0.5, 1.0 - 1e-9);
  EXPECT_EQ(h.renderer.gl_error(), "");
  scene::Pose before(rig), now(rig);
  before.at(scene::Rig::kAllAnimations, 0.5);
  now.at(scene::Rig::kAllAnimations, 1.0 - 1e-9);
  std::vector<glm::dmat4> skin_before, skin_now;
  scene::skin_matrices(rig->skins[0], before.worlds(), skin_before);
  scene::skin_matrices(rig->skins[0], now.worlds(), skin_now);
  // The top face's centre, half a unit from the joint along the tilted axis: the sides between the
  // joints bend, the top turns rigidly with joint 1.
  const glm::dvec3 tilted_top(-0.5 * std::sin(glm::radians(50.0)), 0.5 + 0.5 * std::cos(glm::radians(50.0)), 0);
  const glm::dvec3 point = world_at(h, tilted_top);
  const glm::dvec3 point_before = glm::dvec3(skin_before[1] * glm::inverse(skin_now[1]) * glm::dvec4(point, 1.0));
  const std::vector<glm::vec3> motion = render::read_motion(h.renderer.targets());
  expect_near(motion_at(h, motion, tilted_top), in_view(h, point_before - point), 2e-3f, "the bent top");
  EXPECT_GT(glm::length(point_before - point), 0.05) << "the top moved";
  EXPECT_EQ(motion_at(h, motion, {2.0, 0.0, 2.0}), glm::vec3(0.0f));
}

// A box whose one morph target lifts its top by a unit: the top's motion is the weights' change.
TEST_P(Motion, AMorphsReshapeIsItsPixelsMotion) {
  scene::Mesh box = scene::make_box({-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f}, 1);
  box.morph.weights = {0.0f};
  box.morph.positions.resize(1);
  box.morph.normals.resize(1);
  for (const scene::Vertex& v : box.vertices) {
    box.morph.positions[0].push_back(glm::vec3(0, v.position.y > 0.5f ? 1.0f : 0.0f, 0));
    box.morph.base_normals.push_back(v.normal);
  }
  box.max.y = 2.0f;
  auto rig = std::make_shared<scene::Rig>();
  rig->nodes.resize(1);
  rig->nodes[0].weights = {0.0f};
  scene::AnimationChannel grow;
  grow.node = 0;
  grow.property = scene::AnimatedProperty::weights;
  grow.width = 1;
  grow.times = {0.0f, 2.0f};
  grow.weights = {0.0f, 1.0f};
  rig->animations.push_back({"grow", {grow}, 2.0});
  scene::Scene built = floor_and(std::move(box), rig);
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), std::move(built), motion_frame(), from_the_front()));
  render_two_poses(h, 1.0, 1.5);  // the top from 1.5 to 1.75
  EXPECT_EQ(h.renderer.gl_error(), "");
  std::vector<glm::vec3> motion = render::read_motion(h.renderer.targets());
  expect_near(motion_at(h, motion, {0.0, 1.75, 0.0}), in_view(h, {0, -0.25, 0}), 1e-3f, "the lifted top");
  // The next pose leaves the shape: its previous positions are this one's, so nothing moves.
  render_two_poses(h, 1.5, 1.5);
  motion = render::read_motion(h.renderer.targets());
  EXPECT_EQ(motion_at(h, motion, {0.0, 1.75, 0.0}), glm::vec3(0.0f));
}

// A box coming towards the camera by 5% of its distance a frame: the camera's reprojection finds
// the old depth at its pixels, 5% farther than the point, and starts its history anew every frame
// (the depth test's tolerance is 3%); following the motion, it keeps the history a moving part may
// have (temporal.comp's MOVING_PART_FRAMES, 2).
TEST_P(Motion, APartComingTowardsTheCameraKeepsItsHistory) {
  for (const bool motion_vectors : {true, false}) {
    SCOPED_TRACE(motion_vectors ? "motion vectors" : "camera only");
    render::FrameSettings settings = motion_frame();
    settings.motion_vectors = motion_vectors;
    Harness h;
    ASSERT_TRUE(
        h.start(GetParam(),
                floor_and(scene::make_box({-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f}, 1), sliding_rig({0, 0, -3}, {0, 0, 3}, 2.0f)),
                settings, from_the_front()));
    scene::Pose pose(h.renderer.scene().rig());
    const int frames = 8;
    for (int frame = 0; frame < frames; ++frame) {
      pose.at(scene::Rig::kAllAnimations, 0.2 * frame);  // 0.6 a frame
      h.renderer.pose(pose);
      h.renderer.render(h.camera);
    }
    EXPECT_EQ(h.renderer.gl_error(), "");
    const double z = -3.0 + 0.6 * (frames - 1);
    const glm::ivec2 p = h.pixel_of({0.0, 0.5, z + 0.5});  // the front face's centre
    const std::vector<float> history = render::read_history_frames(h.renderer.targets());
    const float held = history[static_cast<size_t>(p.y * kSize + p.x)];
    if (motion_vectors)
      EXPECT_EQ(held, 2.0f) << "the point's own history, found where it was";
    else
      EXPECT_EQ(held, 1.0f) << "the camera alone finds the point's old depth and a history it rejects";
  }
}

INSTANTIATE_TEST_SUITE_P(Platforms, Motion, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace
