// Node animation: the sampler against closed forms (a cubic the Hermite spline must reproduce,
// slerp at constant angular speed along the shorter arc, STEP and LINEAR), poses through the node
// tree, looping, and the loader's reading and refusals.
#include "scene/animation.h"
#include "gltf_fixture.h"

#include <glm/gtc/matrix_transform.hpp>
#define GLM_ENABLE_EXPERIMENTAL
#include <glm/gtx/string_cast.hpp>

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
                                {"type", components == 4   ? "VEC4"
                                         : components == 1 ? "SCALAR"
                                                           : "VEC3"}});
    doc["animations"] = {{{"name", "slide"},
                          {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", path}}}}}},
                          {"samplers", {{{"input", 2}, {"output", 3}, {"interpolation", interpolation}}}}}};
    return doc;
  }

  // triangle() with one morph target that lifts its top corner (0, 1, 0) by one unit and turns
  // its normals towards +x, shown by node 1 at `rest` weights; its weights animated as `times` and
  // `outputs` give (no animation when `times` is empty).
  json morphing(std::vector<float> rest, std::vector<float> times, std::vector<float> outputs,
                const std::string& interpolation = "LINEAR") {
    json doc = times.empty() ? triangle() : animated("weights", interpolation, times, outputs, 1);
    if (times.empty()) doc["nodes"] = {{{"children", {1}}}, {{"mesh", 0}, {"translation", {1, 0, 0}}}};
    std::vector<unsigned char> bytes;
    append<float>(bytes, {0, 0, 0, 0, 0, 0, 0, 1, 0});     // the target's POSITION
    append<float>(bytes, {0, 0, 1, 0, 0, 1, 0, 0, 1});     // the base NORMAL
    append<float>(bytes, {1, 0, -1, 1, 0, -1, 1, 0, -1});  // the target's NORMAL
    const size_t buffer = doc["buffers"].size(), view = doc["bufferViews"].size(), accessor = doc["accessors"].size();
    doc["buffers"].push_back({{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}});
    for (size_t k = 0; k < 3; ++k) {
      doc["bufferViews"].push_back({{"buffer", buffer}, {"byteOffset", k * 36}, {"byteLength", 36}});
      doc["accessors"].push_back({{"bufferView", view + k}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
    }
    json& primitive = doc["meshes"][0]["primitives"][0];
    primitive["attributes"]["NORMAL"] = accessor + 1;
    primitive["targets"] = {{{"POSITION", accessor}, {"NORMAL", accessor + 2}}};
    doc["meshes"][0]["weights"] = rest;
    if (!times.empty()) doc["animations"][0]["channels"][0]["target"]["node"] = 1;
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

TEST_F(GltfAnimation, CamerasAndLightsOnMovingNodesMoveWithThem) {
  json doc = animated("translation", "LINEAR", {0, 2}, {0, 0, 0, 0, 4, 0}, 3);
  doc["nodes"][0]["children"] = {1, 2};
  doc["nodes"].push_back({{"camera", 0}, {"translation", {0, 0, 5}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
  doc["extensionsUsed"] = {"KHR_lights_punctual"};
  doc["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}}}}}}};
  scene::Scene loaded = load_ok(write(doc));
  ASSERT_EQ(loaded.cameras.size(), 1u);
  ASSERT_EQ(loaded.lights.size(), 1u);
  EXPECT_EQ(loaded.cameras[0].rig_node, 2);
  EXPECT_EQ(loaded.lights[0].rig_node, 2);
  scene::Pose pose(loaded.rig);
  pose.at(scene::Rig::kAllAnimations, 1.0);  // the parent half way up: y = 2
  scene::pose_instances(loaded, pose);
  EXPECT_NEAR(glm::distance(glm::dvec3(loaded.cameras[0].world[3]), glm::dvec3(0, 2, 5)), 0.0, 1e-9);
  EXPECT_NEAR(glm::distance(loaded.lights[0].position, glm::dvec3(0, 2, 5)), 0.0, 1e-9);
  EXPECT_TRUE(loaded.cameras[0].unplaced.empty());
  // A static file's camera and light are carried by nothing.
  EXPECT_EQ(load_ok(write(triangle())).cameras.size(), 0u);
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
  refused(weights, "animations[0].channels[0].target.node: node 0 shows no mesh with morph targets");
  refused(morphing({0}, {0, 2}, {0, 1, 1}), "animations[0].samplers[0].output: 3 values for 2 keys of 1 weights; expected 2");
  refused(morphing({0, 1}, {0, 2}, {0, 1}), "meshes[0].weights: 2 weights; expected one per morph target (1)");
  json node_weights = morphing({0}, {}, {});
  node_weights["nodes"][1]["weights"] = {0.5, 0.5};
  refused(node_weights, "nodes[1].weights: 2 weights; expected one per morph target (1)");
  json short_target = morphing({0}, {0, 2}, {0, 1});
  short_target["accessors"][4]["count"] = 2;
  refused(short_target, "meshes[0].primitives[0].targets[0].POSITION: count 2 differs from POSITION's 3");
}

TEST(AnimationSampler, WeightsInterpolateEachAsAScalar) {
  scene::AnimationChannel weights;
  weights.property = scene::AnimatedProperty::weights;
  weights.width = 2;
  weights.times = {0, 1, 2};
  weights.weights = {0, 1, 0.5f, 0, 1, 0.5f};  // per key: two weights
  float out[2];
  weights.interpolation = scene::Interpolation::linear;
  scene::sample_weights(weights, 0.5, out);
  EXPECT_FLOAT_EQ(out[0], 0.25f);
  EXPECT_FLOAT_EQ(out[1], 0.5f);
  scene::sample_weights(weights, 7.0, out);  // after the last key: the last
  EXPECT_FLOAT_EQ(out[0], 1.0f);
  weights.interpolation = scene::Interpolation::step;
  scene::sample_weights(weights, 1.9, out);
  EXPECT_FLOAT_EQ(out[0], 0.5f);
  EXPECT_FLOAT_EQ(out[1], 0.0f);
  // A cubic spline reproduces w(t) = t^3 (first weight) and 2 - t (second) from values and
  // derivatives, as sample() does for a translation.
  weights.interpolation = scene::Interpolation::cubic_spline;
  weights.weights.clear();
  for (float t : {0.0f, 1.0f, 2.0f})
    for (int part = 0; part < 3; ++part) {
      if (part == 1)
        weights.weights.insert(weights.weights.end(), {t * t * t, 2 - t});
      else
        weights.weights.insert(weights.weights.end(), {3 * t * t, -1.0f});
    }
  for (double t : {0.3, 1.0, 1.6}) {
    scene::sample_weights(weights, t, out);
    EXPECT_NEAR(out[0], t * t * t, 1e-5) << t;
    EXPECT_NEAR(out[1], 2 - t, 1e-6) << t;
  }
}

// A target's TANGENT displacements are not applied: said once for the primitive, and it loads.
TEST_F(GltfAnimation, MorphTargetTangentsAreWarnedNotApplied) {
  json doc = morphing({0}, {0, 2}, {0, 1});
  doc["meshes"][0]["primitives"][0]["targets"][0]["TANGENT"] = doc["meshes"][0]["primitives"][0]["targets"][0]["NORMAL"];
  scene::Scene out;
  scene::LoadReport report;
  ASSERT_TRUE(scene::load_gltf(write(doc), out, report)) << report.error;
  ASSERT_EQ(report.warnings.size(), 1u);
  EXPECT_EQ(report.warnings[0],
            "meshes[0].primitives[0].targets: TANGENT displacements are not applied; a normal map turns with the base tangents, "
            "made orthogonal to the morphed normal");
  ASSERT_EQ(out.meshes.size(), 1u);
  EXPECT_EQ(out.meshes[0].morph.target_count(), 1u);
}

TEST_F(GltfAnimation, MorphTargetsShapeTheMeshAtTheNodesWeightsAndTheAnimationReshapesIt) {
  // Without an animation the mesh is loaded in the shape its weights give and keeps no targets.
  const scene::Scene still = load_ok(write(morphing({0.5}, {}, {})));
  ASSERT_EQ(still.meshes.size(), 1u);
  const auto& v = still.meshes[0].vertices;
  EXPECT_NEAR(v[2].position.y - v[0].position.y, 1.5, 1e-6);
  EXPECT_NEAR(glm::distance(v[0].normal, glm::normalize(glm::vec3(0.5f, 0, 0.5f))), 0.0, 1e-6);
  EXPECT_EQ(still.meshes[0].morph.target_count(), 0u);
  EXPECT_FALSE(still.rig);

  // Animated from 0 to 1 over two seconds, resting at 0.25.
  scene::Scene loaded = load_ok(write(morphing({0.25}, {0, 2}, {0, 1})));
  ASSERT_TRUE(loaded.rig);
  ASSERT_EQ(loaded.meshes.size(), 1u);
  const scene::Mesh& mesh = loaded.meshes[0];
  ASSERT_EQ(mesh.morph.target_count(), 1u);
  EXPECT_EQ(loaded.rig->nodes[1].weights, std::vector<float>{0.25f});
  EXPECT_NEAR(mesh.vertices[2].position.y - mesh.vertices[0].position.y, 1.25, 1e-6);
  // The box holds every shape the keys make: the top corner from y = 1 to 2 above the base.
  EXPECT_NEAR(mesh.max.y - mesh.min.y, 2.0, 1e-6);
  const glm::vec3 base = mesh.vertices[0].position;
  scene::Pose pose(loaded.rig);
  for (double t : {0.0, 0.5, 1.0, 2.0 - 1e-9}) {
    pose.at(scene::Rig::kAllAnimations, t);
    ASSERT_EQ(pose.weights()[1].size(), 1u);
    const float w = static_cast<float>(t / 2);
    EXPECT_NEAR(pose.weights()[1][0], w, 1e-6) << t;
    // The CPU shape against the closed form: the top corner lifted by w, the normals turned.
    std::vector<scene::Vertex> shaped(mesh.vertices.size());
    scene::morph_vertices(mesh, pose.weights()[1].data(), shaped);
    EXPECT_NEAR(glm::distance(shaped[2].position, base + glm::vec3(0, 1 + w, 0)), 0.0, 1e-6) << t;
    EXPECT_NEAR(glm::distance(shaped[1].position, base + glm::vec3(1, 0, 0)), 0.0, 1e-6) << t;
    EXPECT_NEAR(glm::distance(shaped[0].normal, glm::normalize(glm::vec3(w, 0, 1 - w))), 0.0, 1e-6) << t;
  }
  // The render command's pose: the meshes take the shape, the rest pose gives theirs back.
  pose.at(scene::Rig::kAllAnimations, 1.0);
  scene::pose_meshes(loaded, pose);
  EXPECT_NEAR(loaded.meshes[0].vertices[2].position.y - base.y, 1.5, 1e-6);
  EXPECT_EQ(loaded.meshes[0].morph.weights, std::vector<float>{0.5f});
  pose.at(scene::Rig::kNoAnimation, 1.0);
  scene::pose_meshes(loaded, pose);
  EXPECT_NEAR(loaded.meshes[0].vertices[2].position.y - base.y, 1.25, 1e-6);
}

// A skinned triangle: (0,0,0) and (1,0,0) follow joint 0 (node 1, at the origin), (0,2,0) follows
// joint 1 (node 2, one unit up, bound there), which an animation turns 90 degrees about +Z over a
// second. The mesh's own node sits at x = 5, which glTF says a skinned mesh ignores.
class GltfSkin : public GltfLoader {
 protected:
  json skinned() {
    json doc = triangle({0, 0, 0, 1, 0, 0, 0, 2, 0});
    doc["scenes"][0]["nodes"] = {0, 1};
    doc["nodes"] = {{{"mesh", 0}, {"skin", 0}, {"translation", {5, 0, 0}}}, {{"children", {2}}}, {{"translation", {0, 1, 0}}}};
    auto add = [&](std::vector<unsigned char> bytes, int component_type, size_t count, const char* type) {
      const size_t buffer = doc["buffers"].size(), view = doc["bufferViews"].size();
      doc["buffers"].push_back({{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}});
      doc["bufferViews"].push_back({{"buffer", buffer}, {"byteLength", bytes.size()}});
      doc["accessors"].push_back({{"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}});
      return doc["accessors"].size() - 1;
    };
    std::vector<unsigned char> joints, weights, inverse_bind, times, turns;
    append<uint16_t>(joints, {0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0});
    append<float>(weights, {1, 0, 0, 0, 1, 0, 0, 0, 0, 0.5f, 0, 0});  // the last scaled to sum to 1
    append<float>(inverse_bind, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1});
    append<float>(inverse_bind, {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -1, 0, 1});
    append<float>(times, {0, 1});
    const float half = float(std::sqrt(0.5));
    append<float>(turns, {0, 0, 0, 1, 0, 0, half, half});
    json& attributes = doc["meshes"][0]["primitives"][0]["attributes"];
    attributes["JOINTS_0"] = add(joints, 5123, 3, "VEC4");
    attributes["WEIGHTS_0"] = add(weights, 5126, 3, "VEC4");
    doc["skins"] = {{{"joints", {1, 2}}, {"inverseBindMatrices", add(inverse_bind, 5126, 2, "MAT4")}}};
    const size_t input = add(times, 5126, 2, "SCALAR"), output = add(turns, 5126, 2, "VEC4");
    doc["animations"] = {{{"channels", {{{"sampler", 0}, {"target", {{"node", 2}, {"path", "rotation"}}}}}},
                          {"samplers", {{{"input", input}, {"output", output}}}}}};
    return doc;
  }
  // The instance's vertices as the vertex stage moves them, in world space.
  static std::vector<glm::dvec3> skinned_positions(const scene::Scene& loaded) {
    const scene::Instance& instance = loaded.instances[0];
    std::vector<glm::dmat4> matrices;
    for (const glm::dmat4& m : instance.skin_matrices) matrices.push_back(m * instance.offset);
    const scene::Mesh& mesh = loaded.meshes[static_cast<size_t>(instance.mesh)];
    std::vector<scene::Vertex> out(mesh.vertices.size());
    scene::skin_vertices(mesh, matrices, out);
    std::vector<glm::dvec3> positions;
    for (const scene::Vertex& v : out) positions.emplace_back(v.position);
    return positions;
  }
};

TEST_F(GltfSkin, JointsMoveTheirVerticesAndTheMeshsOwnNodeIsIgnored) {
  scene::Scene loaded = load_ok(write(skinned()));
  ASSERT_TRUE(loaded.rig);
  ASSERT_EQ(loaded.rig->skins.size(), 1u);
  ASSERT_EQ(loaded.instances.size(), 1u);
  EXPECT_EQ(loaded.instances[0].skin, 0);
  const scene::Mesh& mesh = loaded.meshes[0];
  ASSERT_EQ(mesh.joints.size(), 3u);
  EXPECT_EQ(mesh.joint_weights[2], glm::vec4(0, 1, 0, 0));
  auto near = [](const glm::dvec3& a, const glm::dvec3& b) { return glm::distance(a, b) < 1e-5; };
  // At rest the bind pose: the vertices where the file put them, not 5 units along x.
  std::vector<glm::dvec3> at = skinned_positions(loaded);
  EXPECT_TRUE(near(at[0], {0, 0, 0}) && near(at[1], {1, 0, 0}) && near(at[2], {0, 2, 0}))
      << glm::to_string(at[0]) << glm::to_string(at[2]);
  scene::Pose pose(loaded.rig);
  for (const auto& [t, expected] :
       std::vector<std::pair<double, glm::dvec3>>{{0.5, {-std::sqrt(0.5), 1 + std::sqrt(0.5), 0}}, {1.0 - 1e-9, {-1, 1, 0}}}) {
    pose.at(scene::Rig::kAllAnimations, t);
    scene::pose_instances(loaded, pose);
    at = skinned_positions(loaded);
    EXPECT_TRUE(near(at[2], expected)) << t << ": " << glm::to_string(at[2]);
    EXPECT_TRUE(near(at[1], {1, 0, 0})) << "joint 0 does not move";
  }
  // The bounds hold every pose: the tip swings from x = 0 to -1.
  scene::Scene framed = load_ok(write(skinned()));
  scene::include_animation_in_bounds(framed);
  EXPECT_NEAR(framed.bounds.min.x, -1.0, 0.01);  // 32 poses over the loop: the last at 87 degrees
  EXPECT_NEAR(framed.bounds.max.y, 2.0, 1e-3);
  EXPECT_LT(framed.bounds.max.x, 1.01) << "the mesh's own node (x = 5) places nothing";
}

TEST_F(GltfSkin, BadSkinsAreRefusedByField) {
  auto refused = [&](const json& doc, const std::string& expected) {
    const std::string error = error_of(write(doc));
    EXPECT_NE(error.find(expected), std::string::npos) << error;
  };
  json far_joint = skinned();
  far_joint["skins"][0]["joints"] = {1};
  far_joint["skins"][0].erase("inverseBindMatrices");
  refused(far_joint,
          "meshes[0].primitives[0].attributes.JOINTS_0: element 2 names joint 1, expected less than the skin's 1 joints");
  json few_matrices = skinned();
  few_matrices["accessors"][4]["count"] = 1;
  refused(few_matrices, "skins[0].inverseBindMatrices: 1 matrices for 2 joints; expected one per joint");
  json hidden = skinned();
  hidden["scenes"][0]["nodes"] = {0};
  refused(hidden, "skins[0].joints[0]: node 1 is not in the shown scene");
  json bad_skin = skinned();
  bad_skin["nodes"][0]["skin"] = 3;
  refused(bad_skin, "nodes[0].skin: 3 out of range (there are 1)");
}

}  // namespace
