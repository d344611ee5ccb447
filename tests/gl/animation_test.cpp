// An animated scene on a real context: a pose moves the draws of the nodes it moves, the frame
// shows them there, and the AO of the old pose is not kept as if the scene stood still.
#include "scene/animation.h"
#include "harness.h"
#include "scene/procedural.h"

namespace {

using test::Harness;

class Animated : public ::testing::TestWithParam<std::string> {};

// A red box on a white floor, carried by its node from x = -1 to x = +1 over two seconds.
TEST_P(Animated, APoseMovesItsNodesDrawsAndTheAoIsComputedAnew) {
  scene::Scene built;
  scene::Material white, red;
  red.base_color = glm::vec4(1, 0, 0, 1);
  built.materials = {white, red};
  scene::add_instance(built, scene::make_quad({-3, 0, 3}, {6, 0, 0}, {0, 0, -6}, 0));
  scene::add_instance(built, scene::make_box({-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f}, 1));
  auto rig = std::make_shared<scene::Rig>();
  rig->nodes.resize(1);
  rig->nodes[0].translation = {-1, 0, 0};
  scene::AnimationChannel slide;
  slide.node = 0;
  slide.property = scene::AnimatedProperty::translation;
  slide.times = {0.0f, 2.0f};
  slide.values = {{-1, 0, 0, 0}, {1, 0, 0, 0}};
  rig->animations.push_back({"slide", {slide}, 2.0});
  built.instances[1].node = 0;
  built.rig = rig;
  scene::Pose pose(rig);
  pose.at(scene::Rig::kAllAnimations, 0.0);
  scene::pose_instances(built, pose);
  scene::update_bounds(built);
  render::FrameSettings settings;
  settings.width = settings.height = 96;
  settings.check_errors = true;
  scene::Framing framing;
  framing.azimuth_deg = 0.0;
  framing.elevation_deg = 30.0;
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), std::move(built), settings, framing));
  for (int frame = 0; frame < 40; ++frame) h.renderer.render(h.camera);
  ASSERT_TRUE(h.renderer.reused_ao()) << "a still camera over a still scene keeps its AO once averaged";
  auto redness = [&](glm::dvec3 world) {
    const std::vector<uint8_t> color = h.renderer.read_color();
    const glm::ivec2 p = h.pixel_of(world);
    const size_t i = static_cast<size_t>(((settings.height - 1 - p.y) * settings.width + p.x) * 4);
    return int(color[i]) - int(color[i + 1]);
  };
  const glm::dvec3 left_top(-1, 1, 0), right_top(0.5, 1, 0);
  EXPECT_GT(redness(left_top), 60);
  EXPECT_LT(redness(right_top), 20);
  pose.at(scene::Rig::kAllAnimations, 1.5);  // three quarters of the way: x = 0.5
  h.renderer.pose(pose.worlds());

  h.renderer.render(h.camera);
  EXPECT_FALSE(h.renderer.reused_ao()) << "the scene moved: its AO is computed again";
  EXPECT_EQ(h.renderer.gl_error(), "");
  EXPECT_LT(redness(left_top), 20);
  EXPECT_GT(redness(right_top), 60);
  // Posed again where it is: nothing moved, so nothing counts as motion.
  const std::uint64_t version = h.renderer.scene().pose_version();
  h.renderer.pose(pose.worlds());
  EXPECT_EQ(h.renderer.scene().pose_version(), version);
}

INSTANTIATE_TEST_SUITE_P(Platforms, Animated, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace
