// An animated scene on a real context: a pose moves the draws of the nodes it moves, the frame
// shows them there, and the AO of the old pose is not kept as if the scene stood still.
#include "scene/animation.h"

#include <glm/gtc/matrix_transform.hpp>
#include "animated_scenes.h"
#include "harness.h"
#include "scene/procedural.h"

namespace {

using test::Harness;

using test::from_the_front;
constexpr int kSize = test::kAnimatedSize;

render::FrameSettings small_frame() {
  return test::small_animated_frame();
}

// For comparing shapes: without temporal accumulation the frame after a pose is that pose's alone
// (with it, a pose that jumps keeps a little of the last pose's AO for a few frames: motion_test.cpp).
render::FrameSettings one_frame_ao() {
  render::FrameSettings settings = small_frame();
  settings.temporal = false;
  return settings;
}

// The pixel where `world` shows in the last frame: its red, and its red less its green (a red
// surface's mark).
glm::ivec2 rgb_at(const Harness& h, glm::dvec3 world) {
  const std::vector<uint8_t> color = h.renderer.read_color();
  const glm::ivec2 p = h.pixel_of(world);
  const size_t i = static_cast<size_t>(((kSize - 1 - p.y) * kSize + p.x) * 4);
  return {color[i], int(color[i]) - int(color[i + 1])};
}
int redness(const Harness& h, glm::dvec3 world) {
  return rgb_at(h, world).y;
}

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
  const render::FrameSettings settings = small_frame();
  const scene::Framing framing = from_the_front(30);
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), std::move(built), settings, framing));
  for (int frame = 0; frame < 40; ++frame) h.renderer.render(h.camera);
  ASSERT_TRUE(h.renderer.reused_ao()) << "a still camera over a still scene keeps its AO once averaged";
  const glm::dvec3 left_top(-1, 1, 0), right_top(0.5, 1, 0);
  EXPECT_GT(redness(h, left_top), 60);
  EXPECT_LT(redness(h, right_top), 20);
  pose.at(scene::Rig::kAllAnimations, 1.5);  // three quarters of the way: x = 0.5
  h.renderer.pose(pose);

  h.renderer.render(h.camera);
  EXPECT_FALSE(h.renderer.reused_ao()) << "the scene moved: its AO is computed again";
  EXPECT_EQ(h.renderer.gl_error(), "");
  EXPECT_LT(redness(h, left_top), 20);
  EXPECT_GT(redness(h, right_top), 60);
  // Posed again where it is: nothing moved, so nothing counts as motion.
  const std::uint64_t version = h.renderer.scene().pose_version();
  h.renderer.pose(pose);
  EXPECT_EQ(h.renderer.scene().pose_version(), version);
}

// A red box whose one morph target lifts its top by a unit, on a white floor: shaped on the GPU's
// side by a pose (the vertices sent again), the frame is the one of the same box shaped on the CPU
// and uploaded as it is.
TEST_P(Animated, APoseReshapesAMorphedMeshAsTheCpuShapesIt) {
  auto build = [](float weight) {
    scene::Scene built;
    scene::Material white, red;
    red.base_color = glm::vec4(1, 0, 0, 1);
    built.materials = {white, red};
    scene::add_instance(built, scene::make_quad({-3, 0, 3}, {6, 0, 0}, {0, 0, -6}, 0));
    scene::Mesh box = scene::make_box({-0.5f, 0.0f, -0.5f}, {0.5f, 1.0f, 0.5f}, 1);
    box.morph.weights = {0.0f};
    box.morph.positions.resize(1);
    box.morph.normals.resize(1);
    for (const scene::Vertex& v : box.vertices) {
      box.morph.positions[0].push_back(glm::vec3(0, v.position.y > 0.5f ? 1.0f : 0.0f, 0));
      box.morph.base_normals.push_back(v.normal);
    }
    box.max.y = 2.0f;  // the box of every shape
    std::vector<scene::Vertex> shaped(box.vertices.size());
    scene::morph_vertices(box, &weight, shaped);
    box.vertices = shaped;
    box.morph.weights = {weight};
    scene::add_instance(built, std::move(box));
    auto rig = std::make_shared<scene::Rig>();
    rig->nodes.resize(1);
    rig->nodes[0].weights = {weight};
    scene::AnimationChannel grow;
    grow.node = 0;
    grow.property = scene::AnimatedProperty::weights;
    grow.width = 1;
    grow.times = {0.0f, 2.0f};
    grow.weights = {0.0f, 1.0f};
    rig->animations.push_back({"grow", {grow}, 2.0});
    built.instances[1].node = 0;
    built.rig = rig;
    scene::update_bounds(built);
    return built;
  };
  const render::FrameSettings settings = one_frame_ao();
  const scene::Framing framing = from_the_front(30);
  const glm::dvec3 above_the_top(0, 1.5, 0);
  std::vector<uint8_t> shaped_on_gpu;
  {
    Harness gpu;  // one context at a time: the two renderers' GL names would coincide
    ASSERT_TRUE(gpu.start(GetParam(), build(0.0f), settings, framing));
    gpu.renderer.render(gpu.camera);
    EXPECT_LT(redness(gpu, above_the_top), 20);
    scene::Pose pose(gpu.renderer.scene().rig());
    pose.at(scene::Rig::kAllAnimations, 1.5);  // weight 0.75: the top at 1.75
    const std::uint64_t version = gpu.renderer.scene().pose_version();
    gpu.renderer.pose(pose);
    EXPECT_GT(gpu.renderer.scene().pose_version(), version) << "a reshaped mesh is a moved scene: its AO is computed again";
    // Enough frames that the AO history of the rest shape is gone from the average.
    for (int frame = 0; frame < 24; ++frame) gpu.renderer.render(gpu.camera);
    EXPECT_EQ(gpu.renderer.gl_error(), "");
    EXPECT_GT(redness(gpu, above_the_top), 60);
    shaped_on_gpu = gpu.renderer.read_color();
  }
  Harness cpu;
  ASSERT_TRUE(cpu.start(GetParam(), build(0.75f), settings, framing));
  for (int frame = 0; frame < 24; ++frame) cpu.renderer.render(cpu.camera);
  const std::vector<uint8_t> shaped_on_cpu = cpu.renderer.read_color();
  ASSERT_EQ(shaped_on_gpu.size(), shaped_on_cpu.size());
  int worst = 0;
  for (size_t i = 0; i < shaped_on_gpu.size(); ++i)
    worst = std::max(worst, std::abs(int(shaped_on_gpu[i]) - int(shaped_on_cpu[i])));
  EXPECT_LE(worst, 2) << "the GPU's shape differs from the CPU's";
}

// A red box whose top half follows a joint that a pose tilts 50 degrees about +Z, on a white floor:
// moved in the vertex stage by the joint matrices, the frame is the one of the same box moved on the
// CPU (scene::skin_vertices) and uploaded unskinned.
TEST_P(Animated, APoseBendsASkinnedMeshAsTheCpuSkinsIt) {
  const std::shared_ptr<scene::Rig> rig = test::tilting_rig();
  auto build = [&](const std::vector<glm::dmat4>* bent) {
    scene::Scene built;
    scene::Material white, red;
    red.base_color = glm::vec4(1, 0, 0, 1);
    built.materials = {white, red};
    scene::add_instance(built, scene::make_quad({-3, 0, 3}, {6, 0, 0}, {0, 0, -6}, 0));
    scene::Mesh box = test::jointed_box();
    if (bent) {  // skinned here, drawn as it is
      std::vector<scene::Vertex> moved(box.vertices.size());
      scene::skin_vertices(box, *bent, moved);
      box.vertices = moved;
      box.joints.clear();
      box.joint_weights.clear();
      scene::add_instance(built, std::move(box));
    } else {
      scene::add_instance(built, std::move(box));
      built.instances[1].skin = 0;
      built.instances[1].node = 0;
      scene::Pose rest(rig);
      scene::skin_matrices(rig->skins[0], rest.worlds(), built.instances[1].skin_matrices);
      built.rig = rig;
    }
    scene::update_bounds(built);
    built.bounds.min = glm::dvec3(-3, 0, -3);  // both framed alike
    built.bounds.max = glm::dvec3(3, 1, 3);
    return built;
  };
  const render::FrameSettings settings = one_frame_ao();
  const scene::Framing framing = from_the_front(30);
  scene::Pose pose(rig);
  pose.at(scene::Rig::kAllAnimations, 1.0 - 1e-9);
  std::vector<glm::dmat4> bent;
  scene::skin_matrices(rig->skins[0], pose.worlds(), bent);
  // Where the tilted top's centre goes: the joint at y = 0.5, the top's centre half a unit above
  // it, turned 50 degrees towards -x.
  const glm::dvec3 tilted_top(-0.5 * std::sin(glm::radians(50.0)) * 0.75, 0.5 + 0.5 * std::cos(glm::radians(50.0)) * 0.75, 0);
  std::vector<uint8_t> bent_on_gpu;
  {
    Harness gpu;  // one context at a time (see above)
    ASSERT_TRUE(gpu.start(GetParam(), build(nullptr), settings, framing));
    gpu.renderer.render(gpu.camera);
    EXPECT_LT(redness(gpu, tilted_top), 20);
    const std::uint64_t version = gpu.renderer.scene().pose_version();
    gpu.renderer.pose(pose);
    EXPECT_GT(gpu.renderer.scene().pose_version(), version) << "a bent mesh is a moved scene";
    for (int frame = 0; frame < 24; ++frame) gpu.renderer.render(gpu.camera);
    EXPECT_EQ(gpu.renderer.gl_error(), "");
    EXPECT_GT(redness(gpu, tilted_top), 60);
    bent_on_gpu = gpu.renderer.read_color();
    const std::uint64_t posed = gpu.renderer.scene().pose_version();
    gpu.renderer.pose(pose);
    EXPECT_EQ(gpu.renderer.scene().pose_version(), posed) << "posed again where it is: nothing moved";
  }
  Harness cpu;
  ASSERT_TRUE(cpu.start(GetParam(), build(&bent), settings, framing));
  for (int frame = 0; frame < 24; ++frame) cpu.renderer.render(cpu.camera);
  const std::vector<uint8_t> bent_on_cpu = cpu.renderer.read_color();
  ASSERT_EQ(bent_on_gpu.size(), bent_on_cpu.size());
  int worst = 0;
  for (size_t i = 0; i < bent_on_gpu.size(); ++i) worst = std::max(worst, std::abs(int(bent_on_gpu[i]) - int(bent_on_cpu[i])));
  EXPECT_LE(worst, 2) << "the vertex stage's skinning differs from the CPU's";
}

// A point light carried by an animated node from above x = -2 to above x = +2 lights the floor
// under it: the pose moves the light the frame uses.
TEST_P(Animated, APoseMovesTheLightsOfMovingNodes) {
  scene::Scene built;
  built.materials = {scene::Material{}};
  built.materials[0].metallic = 0.0f;
  built.materials[0].base_color = glm::vec4(0.1f, 0.1f, 0.1f, 1.0f);  // far from white, where the light shows
  scene::add_instance(built, scene::make_quad({-4, 0, 2}, {8, 0, 0}, {0, 0, -4}, 0));
  auto rig = std::make_shared<scene::Rig>();
  rig->nodes.resize(1);
  rig->nodes[0].translation = {-2, 0.5, 0};
  scene::AnimationChannel slide;
  slide.node = 0;
  slide.property = scene::AnimatedProperty::translation;
  slide.times = {0.0f, 1.0f};
  slide.values = {{-2, 0.5, 0, 0}, {2, 0.5, 0, 0}};
  rig->animations.push_back({"slide", {slide}, 1.0});
  scene::Light light;
  light.type = scene::Light::Type::point;
  light.color = glm::vec3(1.0f);
  light.position = {-2, 0.5, 0};
  light.rig_node = 0;
  built.lights = {light};
  built.rig = rig;
  scene::update_bounds(built);
  const render::FrameSettings settings = small_frame();
  const scene::Framing framing = from_the_front(60);
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), std::move(built), settings, framing));
  auto brightness = [&](glm::dvec3 world) { return rgb_at(h, world).x; };
  const glm::dvec3 left(-2, 0, 0), right(2, 0, 0);
  h.renderer.render(h.camera);
  const int left_lit = brightness(left), right_dark = brightness(right);
  EXPECT_GT(left_lit, right_dark + 40);
  scene::Pose pose(rig);
  pose.at(scene::Rig::kAllAnimations, 1.0 - 1e-9);
  h.renderer.pose(pose);
  h.renderer.render(h.camera);
  EXPECT_EQ(h.renderer.gl_error(), "");
  EXPECT_GT(brightness(right), brightness(left) + 40) << "the light went with its node";
  EXPECT_NEAR(brightness(right), left_lit, 3) << "the same light over the same floor";
}

INSTANTIATE_TEST_SUITE_P(Platforms, Animated, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace
