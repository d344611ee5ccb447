#include "gltf_animation.h"

#include "gltf_accessors.h"
#include "gltf_document.h"

#include <algorithm>
#include <cmath>

namespace scene::gltf {
namespace {

constexpr int kFloat = 5126, kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123;

}  // namespace

std::vector<Animation> read_animations(Document& document, const std::vector<int>& node_of, const Rig& rig) {
  const tinygltf::Model& model = document.model();
  std::vector<Animation> animations;
  for (size_t a = 0; a < model.animations.size(); ++a) {
    const tinygltf::Animation& source = model.animations[a];
    const std::string where = "animations[" + std::to_string(a) + "]";
    Animation animation;
    animation.name = source.name.empty() ? "animation " + std::to_string(a) : source.name;
    for (size_t c = 0; c < source.channels.size(); ++c) {
      const tinygltf::AnimationChannel& channel = source.channels[c];
      const std::string field = where + ".channels[" + std::to_string(c) + "]";
      if (channel.sampler < 0 || static_cast<size_t>(channel.sampler) >= source.samplers.size())
        fail(field + ".sampler: " + std::to_string(channel.sampler) + " out of range (there are " +
             std::to_string(source.samplers.size()) + ")");
      if (channel.target_node < 0) continue;  // an extension's target, or none: nothing of ours moves
      if (static_cast<size_t>(channel.target_node) >= model.nodes.size())
        fail(field + ".target.node: " + std::to_string(channel.target_node) + " out of range (there are " +
             std::to_string(model.nodes.size()) + ")");
      AnimationChannel out;
      if (channel.target_path == "translation")
        out.property = AnimatedProperty::translation;
      else if (channel.target_path == "rotation")
        out.property = AnimatedProperty::rotation;
      else if (channel.target_path == "scale")
        out.property = AnimatedProperty::scale;
      else if (channel.target_path == "weights")
        out.property = AnimatedProperty::weights;
      else
        fail(field + ".target.path: \"" + channel.target_path + "\"; expected translation, rotation, scale or weights");
      const int node = node_of[static_cast<size_t>(channel.target_node)];
      if (node < 0) continue;  // a node of another scene than the one shown
      if (out.property != AnimatedProperty::weights && rig.nodes[static_cast<size_t>(node)].uses_matrix)
        fail(field + ".target.node: node " + std::to_string(channel.target_node) +
             " has a matrix; glTF animates only nodes given by translation, rotation and scale");
      out.node = node;
      if (out.property == AnimatedProperty::weights) {
        out.width = rig.nodes[static_cast<size_t>(node)].weights.size();
        if (out.width == 0)
          fail(field + ".target.node: node " + std::to_string(channel.target_node) +
               " shows no mesh with morph targets; expected one for a weights channel");
      }
      const tinygltf::AnimationSampler& sampler = source.samplers[static_cast<size_t>(channel.sampler)];
      const std::string sampler_field = where + ".samplers[" + std::to_string(channel.sampler) + "]";
      if (sampler.interpolation == "STEP")
        out.interpolation = Interpolation::step;
      else if (sampler.interpolation == "LINEAR" || sampler.interpolation.empty())
        out.interpolation = Interpolation::linear;
      else if (sampler.interpolation == "CUBICSPLINE")
        out.interpolation = Interpolation::cubic_spline;
      else
        fail(sampler_field + ".interpolation: \"" + sampler.interpolation + "\"; expected LINEAR, STEP or CUBICSPLINE");
      const auto times = read_floats<1>(document, sampler.input, sampler_field + ".input", {{kFloat, false}});
      if (times.empty()) fail(sampler_field + ".input: expected at least one key");
      for (size_t k = 0; k < times.size(); ++k) {
        if (times[k].x < 0.0f) fail(sampler_field + ".input: key " + std::to_string(k) + " is negative; expected seconds >= 0");
        if (k > 0 && !(times[k].x > times[k - 1].x))
          fail(sampler_field + ".input: key " + std::to_string(k) + " is not after the one before; expected increasing times");
        out.times.push_back(times[k].x);
      }
      const size_t per_key = out.interpolation == Interpolation::cubic_spline ? 3 : 1;
      const std::string output_field = sampler_field + ".output";
      if (out.property == AnimatedProperty::weights) {
        const std::vector<Format> formats = {
            {kFloat, false}, {kByte, true}, {kUnsignedByte, true}, {kShort, true}, {kUnsignedShort, true}};
        for (const glm::vec1& w : read_floats<1>(document, sampler.output, output_field, formats)) out.weights.push_back(w.x);
        if (out.weights.size() != out.times.size() * per_key * out.width)
          fail(output_field + ": " + std::to_string(out.weights.size()) + " values for " + std::to_string(out.times.size()) +
               " keys of " + std::to_string(out.width) + " weights; expected " +
               std::to_string(out.times.size() * per_key * out.width));
      } else if (out.property == AnimatedProperty::rotation) {
        // glTF allows normalised integers for rotations (KHR_mesh_quantization's pipelines write them).
        const std::vector<Format> formats = {
            {kFloat, false}, {kByte, true}, {kUnsignedByte, true}, {kShort, true}, {kUnsignedShort, true}};
        for (const glm::vec4& q : read_floats<4>(document, sampler.output, output_field, formats)) out.values.push_back(q);
      } else {
        for (const glm::vec3& v : read_floats<3>(document, sampler.output, output_field, {{kFloat, false}}))
          out.values.emplace_back(v, 0.0f);
      }
      if (out.property != AnimatedProperty::weights && out.values.size() != out.times.size() * per_key)
        fail(output_field + ": " + std::to_string(out.values.size()) + " values for " + std::to_string(out.times.size()) +
             " keys; expected " + std::to_string(out.times.size() * per_key));
      if (out.property == AnimatedProperty::rotation)
        for (size_t k = 0; k < out.values.size(); ++k)
          if (per_key == 1 || k % 3 == 1) {
            if (glm::length(out.values[k]) < 1e-6f)
              fail(output_field + ": key " + std::to_string(k / per_key) + " is a zero quaternion; expected a unit one");
            out.values[k] = glm::normalize(out.values[k]);
          }
      animation.duration = std::max(animation.duration, double(out.times.back()));
      animation.channels.push_back(std::move(out));
    }
    animations.push_back(std::move(animation));
  }
  return animations;
}

}  // namespace scene::gltf
