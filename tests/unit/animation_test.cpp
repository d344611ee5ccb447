// Node animation: the sampler against closed forms (a cubic the Hermite spline must reproduce,
// slerp at constant angular speed along the shorter arc, STEP and LINEAR), poses through the node
// tree, looping, and the loader's reading and refusals.
#include "scene/animation.h"
#include "gltf_fixture.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

namespace {

scene::AnimationChannel channel(scene::AnimatedProperty property, scene::Interpolation interpolation, std::vector<float> times,
                                std::vector<glm::vec4> values) {
  scene::AnimationChannel c;
  c.property = property;
  c.interpolation = interpolation;
  c.times = std::move(times);
  c.values = std::move(values);
  return c;
}

glm::vec4 about(glm::vec3 axis, double degrees) {  // glTF's x y z w
  const double half = glm::radians(degrees) / 2;
  return glm::vec4(glm::vec3(glm::normalize(axis) * float(std::sin(half))), float(std::cos(half)));
}

double angle_about(const glm::dvec4& q, glm::dvec3 axis) {
  return glm::degrees(2.0 * std::atan2(glm::dot(glm::dvec3(q), glm::normalize(axis)), q.w));
}

TEST(AnimationSampler, StepHoldsAndLinearInterpolatesAndTheEndsClamp) {
  using scene::AnimatedProperty, scene::Interpolation;
  const auto step =
      channel(AnimatedProperty::translation, Interpolation::step, {1, 2, 4}, {{0, 0, 0, 0}, {2, 0, 0, 0}, {6, 0, 0, 0}});
  EXPECT_EQ(scene::sample(step, 1.99).x, 0.0);
  EXPECT_EQ(scene::sample(step, 2.0).x, 2.0);
  EXPECT_EQ(scene::sample(step, 3.9).x, 2.0);
  auto linear = step;
  linear.interpolation = Interpolation::linear;
  EXPECT_DOUBLE_EQ(scene::sample(linear, 1.5).x, 1.0);
  EXPECT_DOUBLE_EQ(scene::sample(linear, 3.0).x, 4.0);
  EXPECT_EQ(scene::sample(linear, 0.0).x, 0.0);   // before the first key: the first
  EXPECT_EQ(scene::sample(linear, 10.0).x, 6.0);  // after the last: the last
}

// p(t) = t^3 on keys 0, 1, 2 with its derivative 3 t^2 as both tangents: the Hermite spline is
// exact for a cubic, so every time between the keys lands on it.
TEST(AnimationSampler, CubicSplineReproducesACubicFromItsValuesAndDerivatives) {
  std::vector<glm::vec4> values;
  for (float t : {0.0f, 1.0f, 2.0f}) {
    const glm::vec4 derivative(3 * t * t, 0, 0, 0), value(t * t * t, 0, 0, 0);
    values.insert(values.end(), {derivative, value, derivative});  // in-tangent, value, out-tangent
  }
  const auto cubic = channel(scene::AnimatedProperty::translation, scene::Interpolation::cubic_spline, {0, 1, 2}, values);
  for (double t : {0.0, 0.25, 0.5, 0.9, 1.0, 1.3, 1.75, 2.0}) EXPECT_NEAR(scene::sample(cubic, t).x, t * t * t, 1e-9) << t;
  // Unequal spans: the tangents are per second, scaled by each span (keys 0, 0.5, 2).
  std::vector<glm::vec4> uneven;
  for (float t : {0.0f, 0.5f, 2.0f}) {
    const glm::vec4 derivative(3 * t * t, 0, 0, 0);
    uneven.insert(uneven.end(), {derivative, glm::vec4(t * t * t, 0, 0, 0), derivative});
  }
  const auto stretched = channel(scene::AnimatedProperty::translation, scene::Interpolation::cubic_spline, {0, 0.5f, 2}, uneven);
  for (double t : {0.2, 0.7, 1.4}) EXPECT_NEAR(scene::sample(stretched, t).x, t * t * t, 1e-6) << t;
}

TEST(AnimationSampler, RotationsSlerpAtConstantSpeedAlongTheShorterArc) {
  const glm::dvec3 z(0, 0, 1), y(0, 1, 0);
  auto linear = channel(scene::AnimatedProperty::rotation, scene::Interpolation::linear, {0, 1}, {about(z, 0), about(z, 90)});
  for (double u : {0.1, 0.25, 0.5, 0.8}) EXPECT_NEAR(angle_about(scene::sample(linear, u), z), 90.0 * u, 1e-4) << u;
  // -q is q: 0 to 160 degrees written as the negated quaternion still turns 80 degrees at the
  // middle, not the long way round (-100).
  glm::vec4 far = about(y, 160);
  linear.values = {about(y, 0), -far};
  const glm::dvec4 middle = scene::sample(linear, 0.5);
  EXPECT_NEAR(std::abs(angle_about(middle, y)), 80.0, 1e-4);
  EXPECT_NEAR(glm::length(middle), 1.0, 1e-6);  // the keys are floats
}

// A parent turning about +Y carries its child (one unit along +X) round; the child's own
// translation animation adds to that; the selection loops over its longest animation.
TEST(AnimationPose, NodesFollowTheirParentsAndTheSelectionLoops) {
  auto rig = std::make_shared<scene::Rig>();
  rig->nodes.resize(2);
  rig->nodes[1].parent = 0;
  rig->nodes[1].translation = {1, 0, 0};
  scene::Animation turn;
  turn.name = "turn";
  turn.channels.push_back(channel(scene::AnimatedProperty::rotation, scene::Interpolation::linear, {0, 4},
                                  {about({0, 1, 0}, 0), about({0, 1, 0}, 180)}));
  turn.channels.back().node = 0;
  turn.duration = 4;
  scene::Animation lift;
  lift.name = "lift";
  lift.channels.push_back(
      channel(scene::AnimatedProperty::translation, scene::Interpolation::linear, {0, 2}, {{1, 0, 0, 0}, {1, 2, 0, 0}}));
  lift.channels.back().node = 1;
  lift.duration = 2;
  rig->animations = {turn, lift};
  scene::Pose pose(rig);
  auto child_at = [&](int selection, double t) {
    pose.at(selection, t);
    return glm::dvec3(pose.worlds()[1][3]);
  };
  // Half a turn's half: 90 degrees, +X to -Z.
  EXPECT_NEAR(glm::distance(child_at(0, 2.0), glm::dvec3(0, 0, -1)), 0.0, 1e-9);
  EXPECT_NEAR(glm::distance(child_at(1, 1.0), glm::dvec3(1, 1, 0)), 0.0, 1e-9);
  EXPECT_NEAR(glm::distance(child_at(scene::Rig::kAllAnimations, 2.0), glm::dvec3(0, 2, -1)), 0.0, 1e-6);
  EXPECT_NEAR(glm::distance(child_at(scene::Rig::kNoAnimation, 2.0), glm::dvec3(1, 0, 0)), 0.0, 1e-12);
  // All loop over 4 s (the longest), "lift" alone over its 2 s.
  EXPECT_NEAR(glm::distance(child_at(scene::Rig::kAllAnimations, 5.0), child_at(scene::Rig::kAllAnimations, 1.0)), 0.0, 1e-9);
  EXPECT_NEAR(glm::distance(child_at(1, 2.5), child_at(1, 0.5)), 0.0, 1e-9);
  int selection = 0;
  std::string error;
  EXPECT_TRUE(scene::select_animation(rig.get(), "lift", selection, error));
  EXPECT_EQ(selection, 1);
  EXPECT_TRUE(scene::select_animation(rig.get(), "0", selection, error));
  EXPECT_EQ(selection, 0);
  EXPECT_TRUE(scene::select_animation(rig.get(), "none", selection, error));
  EXPECT_EQ(selection, scene::Rig::kNoAnimation);
  EXPECT_FALSE(scene::select_animation(rig.get(), "jump", selection, error));
  EXPECT_EQ(error, "no animation named \"jump\" (expected all, none, an index or one of: \"turn\", \"lift\")");
  EXPECT_FALSE(scene::select_animation(nullptr, "2", selection, error));
  EXPECT_EQ(error, "animation 2 out of range (the scene has 0)");
}

class GltfAnimation : public GltfLoader {
 protected:
  // triangle() under a parent node, with one animation of `path` on the parent: keys at `times`.
  json animated(const std::string& path, const std::string& interpolation, std::vector<float> times, std::vector<float> outputs,
                int components) {
    json doc = triangle();
    doc["nodes"] = {{{"children", {1}}, {"translation", {0, 0, 0}}}, {{"mesh", 0}, {"translation", {1, 0, 0}}}};
    std::vector<unsigned char> bytes;
    for (float t : times) append<float>(bytes, {t});
    const size_t output_offset = bytes.size();
    for (float v : outputs) append<float>(bytes, {v});
    doc["buffers"].push_back({{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}});
    doc["bufferViews"].push_back({{"buffer", 1}, {"byteLength", output_offset}});
    doc["bufferViews"].push_back({{"buffer", 1}, {"byteOffset", output_offset}, {"byteLength", outputs.size() * 4}});
    doc["accessors"].push_back({{"bufferView", 2}, {"componentType", 5126}, {"count", times.size()}, {"type", "SCALAR"}});
    doc["accessors"].push_back({{"bufferView", 3},
                                {"componentType", 5126},
                                {"count", outputs.size() / static_cast<size_t>(components)},
                                {"type", components == 4 ? "VEC4" : "VEC3"}});
    doc["animations"] = {{{"name", "slide"},
                          {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", path}}}}}},
                          {"samplers", {{{"input", 2}, {"output", 3}, {"interpolation", interpolation}}}}}};
    return doc;
  }
};

TEST_F(GltfAnimation, ChannelsMoveTheRigsNodesAndTheRenderPoseFollows) {
  const json doc = animated("translation", "LINEAR", {0, 2}, {0, 0, 0, 0, 4, 0}, 3);
  scene::Scene loaded = load_ok(write(doc));
  ASSERT_TRUE(loaded.rig);
  ASSERT_EQ(loaded.rig->nodes.size(), 2u);
  EXPECT_EQ(loaded.rig->nodes[1].parent, 0);
  ASSERT_EQ(loaded.rig->animations.size(), 1u);
  EXPECT_EQ(loaded.rig->animations[0].name, "slide");
  EXPECT_EQ(loaded.rig->animations[0].duration, 2.0);
  ASSERT_EQ(loaded.instances.size(), 1u);
  EXPECT_EQ(loaded.instances[0].node, 1);
  scene::Pose pose(loaded.rig);
  pose.at(scene::Rig::kAllAnimations, 1.0);
  const glm::dvec3 rest_corner = glm::dvec3(loaded.instances[0].world * glm::dvec4(glm::dvec3(loaded.meshes[0].min), 1.0));
  scene::pose_instances(loaded, pose);
  const glm::dvec3 posed_corner = glm::dvec3(loaded.instances[0].world * glm::dvec4(glm::dvec3(loaded.meshes[0].min), 1.0));
  EXPECT_NEAR(glm::distance(posed_corner - rest_corner, glm::dvec3(0, 2, 0)), 0.0, 1e-9);
  // The bounds hold the whole animation (the triangle's y from 0 to 1, carried up to 4), so every
  // pose is framed alike and nothing moves out of view.
  EXPECT_NEAR(loaded.bounds.max.y, 1.0, 1e-6);
  scene::include_animation_in_bounds(loaded);
  EXPECT_NEAR(loaded.bounds.min.y, 0.0, 1e-6);
  EXPECT_GT(loaded.bounds.max.y, 4.8);
  EXPECT_EQ(loaded.instances[0].world, pose.worlds()[1] * loaded.instances[0].offset);  // the instances are kept
  // A static file keeps no rig.
  EXPECT_FALSE(load_ok(write(triangle())).rig);
}

TEST_F(GltfAnimation, BadSamplersAreRefusedByFieldAndWeightsWarned) {
  auto refused = [&](const json& doc, const std::string& expected) {
    const std::string error = error_of(write(doc));
    EXPECT_NE(error.find(expected), std::string::npos) << error;
  };
  refused(animated("translation", "LINEAR", {1, 0.5f}, {0, 0, 0, 0, 4, 0}, 3),
          "animations[0].samplers[0].input: key 1 is not after the one before; expected increasing times");
  refused(animated("translation", "CUBICSPLINE", {0, 1}, {0, 0, 0, 0, 4, 0}, 3),
          "animations[0].samplers[0].output: 2 values for 2 keys; expected 6");
  refused(animated("rotation", "LINEAR", {0, 1}, {0, 0, 0, 0, 0, 0, 0, 1}, 4),
          "animations[0].samplers[0].output: key 0 is a zero quaternion; expected a unit one");
  refused(animated("translation", "SMOOTH", {0, 1}, {0, 0, 0, 0, 4, 0}, 3),
          "animations[0].samplers[0].interpolation: \"SMOOTH\"; expected LINEAR, STEP or CUBICSPLINE");
  json matrix = animated("translation", "LINEAR", {0, 2}, {0, 0, 0, 0, 4, 0}, 3);
  matrix["nodes"][0].erase("translation");
  matrix["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  refused(matrix, "animations[0].channels[0].target.node: node 0 has a matrix");
  json weights = animated("translation", "LINEAR", {0, 2}, {0, 0, 0, 0, 4, 0}, 3);
  weights["animations"][0]["channels"][0]["target"]["path"] = "weights";
  scene::Scene out;
  scene::LoadReport report;
  ASSERT_TRUE(scene::load_gltf(write(weights), out, report)) << report.error;
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_NE(report.warnings[0].find("morph target weights are not animated"), std::string::npos);
}

}  // namespace
