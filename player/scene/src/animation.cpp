#include "scene/animation.h"

#include "scene/scene.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace scene {
namespace {

glm::dquat as_quaternion(const glm::dvec4& xyzw) {
  return glm::dquat(xyzw.w, xyzw.x, xyzw.y, xyzw.z);
}

glm::dvec4 slerp_shorter(glm::dvec4 a, glm::dvec4 b, double u) {
  double cosine = glm::dot(a, b);
  // q and -q are one rotation: the shorter arc goes to whichever of them is nearer.
  if (cosine < 0.0) {
    b = -b;
    cosine = -cosine;
  }
  if (cosine > 0.9995) return glm::normalize(glm::mix(a, b, u));  // nearly equal: the arc is a line
  const double angle = std::acos(cosine);
  return (std::sin((1.0 - u) * angle) * a + std::sin(u * angle) * b) / std::sin(angle);
}

}  // namespace

glm::dmat4 trs_matrix(const glm::dvec3& translation, const glm::dquat& rotation, const glm::dvec3& scale) {
  glm::dmat4 transform = glm::translate(glm::dmat4(1.0), translation);
  transform *= glm::mat4_cast(rotation);
  return glm::scale(transform, scale);
}

double Rig::duration(int selection) const {
  double longest = 0.0;
  for (size_t i = 0; i < animations.size(); ++i)
    if (selection == kAllAnimations || static_cast<size_t>(selection) == i) longest = std::max(longest, animations[i].duration);
  return longest;
}

bool select_animation(const Rig* rig, const std::string& spec, int& selection, std::string& error) {
  if (spec == "all" || spec.empty()) {
    selection = Rig::kAllAnimations;
    return true;
  }
  if (spec == "none") {
    selection = Rig::kNoAnimation;
    return true;
  }
  const size_t count = rig ? rig->animations.size() : 0;
  char* end = nullptr;
  const long index = std::strtol(spec.c_str(), &end, 10);
  if (end != spec.c_str() && *end == '\0') {
    if (index < 0 || static_cast<size_t>(index) >= count) {
      error = "animation " + spec + " out of range (the scene has " + std::to_string(count) + ")";
      return false;
    }
    selection = static_cast<int>(index);
    return true;
  }
  for (size_t i = 0; i < count; ++i)
    if (rig->animations[i].name == spec) {
      selection = static_cast<int>(i);
      return true;
    }
  std::string names;
  for (size_t i = 0; i < count; ++i) names += (i ? ", \"" : "\"") + rig->animations[i].name + "\"";
  error = "no animation named \"" + spec +
          "\" (expected all, none, an index or one of: " + (names.empty() ? "none in the scene" : names) + ")";
  return false;
}

void skin_matrices(const Rig::Skin& skin, const std::vector<glm::dmat4>& node_worlds, std::vector<glm::dmat4>& out) {
  out.resize(skin.joints.size());
  for (size_t j = 0; j < skin.joints.size(); ++j)
    out[j] = node_worlds[static_cast<size_t>(skin.joints[j])] * skin.inverse_bind[j];
}

void pose_instances(Scene& scene, const Pose& pose) {
  for (Instance& instance : scene.instances) {
    if (instance.skin >= 0) {
      const Rig::Skin& skin = pose.rig().skins[static_cast<size_t>(instance.skin)];
      skin_matrices(skin, pose.worlds(), instance.skin_matrices);
      instance.world = pose.worlds()[static_cast<size_t>(skin.joints[0])];
    } else if (instance.node >= 0) {
      instance.world = pose.worlds()[static_cast<size_t>(instance.node)] * instance.offset;
    }
  }
  pose_lights(scene.lights, pose);
  pose_cameras(scene.cameras, pose);
}

bool pose_lights(std::vector<Light>& lights, const Pose& pose) {
  bool moved = false;
  for (Light& light : lights) {
    if (light.rig_node < 0) continue;
    const glm::dvec3 position = light.position, direction = light.direction;
    place_light(light, pose.worlds()[static_cast<size_t>(light.rig_node)]);
    moved = moved || position != light.position || direction != light.direction;
  }
  return moved;
}

void pose_cameras(std::vector<FileCamera>& cameras, const Pose& pose) {
  for (FileCamera& camera : cameras)
    if (camera.rig_node >= 0) place_camera(camera, pose.worlds()[static_cast<size_t>(camera.rig_node)]);
}

void pose_meshes(Scene& scene, const Pose& pose) {
  std::vector<Vertex> shaped;
  for (const Instance& instance : scene.instances) {
    Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    if (instance.node < 0 || mesh.morph.target_count() == 0) continue;
    const std::vector<float>& weights = pose.weights()[static_cast<size_t>(instance.node)];
    if (weights.size() != mesh.morph.target_count()) continue;
    shaped.resize(mesh.vertices.size());
    morph_vertices(mesh, weights.data(), shaped);
    mesh.vertices.swap(shaped);
    mesh.morph.weights = weights;
  }
}

void include_animation_in_bounds(Scene& scene) {
  if (!scene.rig || scene.rig->animations.empty()) return;
  constexpr int kSamples = 32;
  const std::vector<Instance> rest = scene.instances;
  Bounds all = scene.bounds;
  Pose pose(scene.rig);
  for (int selection = Rig::kAllAnimations; selection < static_cast<int>(scene.rig->animations.size()); ++selection) {
    const double duration = scene.rig->duration(selection);
    for (int k = 0; k < kSamples; ++k) {
      pose.at(selection, duration * k / kSamples);
      pose_instances(scene, pose);
      update_bounds(scene);
      all.min = glm::min(all.min, scene.bounds.min);
      all.max = glm::max(all.max, scene.bounds.max);
    }
  }
  scene.instances = rest;
  scene.bounds = all;
}

glm::dvec4 sample(const AnimationChannel& channel, double seconds) {
  const std::vector<float>& times = channel.times;
  const bool cubic = channel.interpolation == Interpolation::cubic_spline;
  auto value = [&](size_t key) { return glm::dvec4(channel.values[cubic ? key * 3 + 1 : key]); };
  const bool rotation = channel.property == AnimatedProperty::rotation;
  if (times.empty()) return glm::dvec4(0.0);
  if (seconds <= times.front()) return value(0);
  if (seconds >= times.back()) return value(times.size() - 1);
  const size_t next = static_cast<size_t>(std::upper_bound(times.begin(), times.end(), seconds) - times.begin());
  const size_t key = next - 1;
  const double span = double(times[next]) - double(times[key]);
  const double u = (seconds - times[key]) / span;
  switch (channel.interpolation) {
    case Interpolation::step:
      return value(key);
    case Interpolation::linear:
      return rotation ? slerp_shorter(value(key), value(next), u) : glm::mix(value(key), value(next), u);
    case Interpolation::cubic_spline: {
      // glTF 2.0, Appendix C: Hermite between the keys, tangents scaled by the keys' distance.
      const glm::dvec4 p0 = value(key), p1 = value(next);
      const glm::dvec4 m0 = span * glm::dvec4(channel.values[key * 3 + 2]);
      const glm::dvec4 m1 = span * glm::dvec4(channel.values[next * 3]);
      const double u2 = u * u, u3 = u2 * u;
      const glm::dvec4 p = (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * p1 + (u3 - u2) * m1;
      return rotation ? glm::normalize(p) : p;
    }
  }
  return value(key);
}

void sample_weights(const AnimationChannel& channel, double seconds, float* out) {
  const std::vector<float>& times = channel.times;
  const size_t width = channel.width;
  const bool cubic = channel.interpolation == Interpolation::cubic_spline;
  // Weight w of key k (part 0: in-tangent, 1: value, 2: out-tangent of a cubic spline).
  auto at = [&](size_t key, size_t part, size_t w) {
    return double(channel.weights[((cubic ? key * 3 + part : key) * width) + w]);
  };
  if (times.empty()) return;
  size_t key = 0, next = 0;
  double u = 0.0, span = 0.0;
  if (seconds >= times.back()) {
    key = next = times.size() - 1;
  } else if (seconds > times.front()) {
    next = static_cast<size_t>(std::upper_bound(times.begin(), times.end(), seconds) - times.begin());
    key = next - 1;
    span = double(times[next]) - double(times[key]);
    u = (seconds - times[key]) / span;
  }
  for (size_t w = 0; w < width; ++w) {
    double value = at(key, 1, w);
    if (key != next && channel.interpolation == Interpolation::linear) {
      value = value + (at(next, 1, w) - value) * u;
    } else if (key != next && cubic) {
      const double u2 = u * u, u3 = u2 * u;
      value = (2 * u3 - 3 * u2 + 1) * value + (u3 - 2 * u2 + u) * span * at(key, 2, w) + (-2 * u3 + 3 * u2) * at(next, 1, w) +
              (u3 - u2) * span * at(next, 0, w);
    }
    out[w] = static_cast<float>(value);
  }
}

Pose::Pose(std::shared_ptr<const Rig> rig)
    : rig_(std::move(rig)), locals_(rig_->nodes.size()), worlds_(rig_->nodes.size(), glm::dmat4(1.0)) {
  for (const Rig::Node& node : rig_->nodes) weights_.push_back(node.weights);
  at(Rig::kAllAnimations, 0.0);
}

void Pose::at(int selection, double seconds) {
  const Rig& rig = *rig_;
  for (size_t i = 0; i < rig.nodes.size(); ++i) {
    locals_[i] = {rig.nodes[i].translation, rig.nodes[i].rotation, rig.nodes[i].scale};
    std::copy(rig.nodes[i].weights.begin(), rig.nodes[i].weights.end(), weights_[i].begin());
  }
  const double duration = rig.duration(selection);
  const double t = duration > 0.0 && std::isfinite(seconds) ? seconds - duration * std::floor(seconds / duration) : 0.0;
  for (size_t a = 0; a < rig.animations.size(); ++a) {
    if (selection != Rig::kAllAnimations && static_cast<size_t>(selection) != a) continue;
    for (const AnimationChannel& channel : rig.animations[a].channels) {
      if (channel.property == AnimatedProperty::weights) {
        sample_weights(channel, t, weights_[static_cast<size_t>(channel.node)].data());
        continue;
      }
      const glm::dvec4 v = sample(channel, t);
      Local& local = locals_[static_cast<size_t>(channel.node)];
      switch (channel.property) {
        case AnimatedProperty::translation:
          local.translation = glm::dvec3(v);
          break;
        case AnimatedProperty::rotation:
          local.rotation = glm::normalize(as_quaternion(v));
          break;
        case AnimatedProperty::scale:
          local.scale = glm::dvec3(v);
          break;
        case AnimatedProperty::weights:
          break;
      }
    }
  }
  for (size_t i = 0; i < rig.nodes.size(); ++i) {
    const Rig::Node& node = rig.nodes[i];
    const Local& local = locals_[i];
    const glm::dmat4 transform = node.uses_matrix ? node.matrix : trs_matrix(local.translation, local.rotation, local.scale);
    worlds_[i] = node.parent < 0 ? transform : worlds_[static_cast<size_t>(node.parent)] * transform;
  }
}

}  // namespace scene
