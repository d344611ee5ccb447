#pragma once
// Small animated scenes the animation and motion tests share.
#include "render/settings.h"
#include "scene/animation.h"
#include "scene/camera.h"
#include "scene/procedural.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <memory>

namespace test {

constexpr int kAnimatedSize = 96;

// A small frame with GL errors checked after each pass.
inline render::FrameSettings small_animated_frame() {
  render::FrameSettings settings;
  settings.width = settings.height = kAnimatedSize;
  settings.check_errors = true;
  return settings;
}

// Looking along -Z from `elevation_deg` above the horizon.
inline scene::Framing from_the_front(double elevation_deg) {
  scene::Framing framing;
  framing.azimuth_deg = 0.0;
  framing.elevation_deg = elevation_deg;
  return framing;
}

// Two joints: 0 at the origin, 1 half a unit above it, which the animation "tilt" turns 50 degrees
// about +Z over a second (LINEAR).
inline std::shared_ptr<scene::Rig> tilting_rig() {
  auto rig = std::make_shared<scene::Rig>();
  rig->nodes.resize(2);
  rig->nodes[1].parent = 0;
  rig->nodes[1].translation = {0, 0.5, 0};
  scene::Rig::Skin skin;
  skin.joints = {0, 1};
  skin.inverse_bind = {glm::dmat4(1.0), glm::translate(glm::dmat4(1.0), glm::dvec3(0, -0.5, 0))};
  rig->skins = {skin};
  scene::AnimationChannel tilt;
  tilt.node = 1;
  tilt.property = scene::AnimatedProperty::rotation;
  const double half = glm::radians(50.0) / 2;
  tilt.times = {0.0f, 1.0f};
  tilt.values = {{0, 0, 0, 1}, {0, 0, float(std::sin(half)), float(std::cos(half))}};
  rig->animations.push_back({"tilt", {tilt}, 1.0});
  return rig;
}

// A box of material 1, 0.5 wide and a unit tall on the origin, whose top half follows joint 1.
inline scene::Mesh jointed_box() {
  scene::Mesh box = scene::make_box({-0.25f, 0.0f, -0.25f}, {0.25f, 1.0f, 0.25f}, 1);
  for (const scene::Vertex& v : box.vertices) {
    box.joints.push_back({v.position.y > 0.5f ? 1 : 0, 0, 0, 0});
    box.joint_weights.emplace_back(1, 0, 0, 0);
  }
  return box;
}

}  // namespace test
