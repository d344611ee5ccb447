#include "gltf_morph.h"

#include "gltf_accessors.h"
#include "gltf_document.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace scene::gltf {
namespace {

constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT, kByte = TINYGLTF_COMPONENT_TYPE_BYTE,
              kShort = TINYGLTF_COMPONENT_TYPE_SHORT;

}  // namespace

size_t target_count(const tinygltf::Mesh& mesh, const std::string& where) {
  for (size_t p = 1; p < mesh.primitives.size(); ++p)
    if (mesh.primitives[p].targets.size() != mesh.primitives[0].targets.size())
      fail(where + ".primitives[" + std::to_string(p) + "].targets: " + std::to_string(mesh.primitives[p].targets.size()) +
           " targets; expected as many as primitives[0] has (" + std::to_string(mesh.primitives[0].targets.size()) + ")");
  return mesh.primitives.empty() ? 0 : mesh.primitives[0].targets.size();
}

Mesh::Morph read_morph_targets(Document& document, const tinygltf::Primitive& primitive, size_t vertex_count,
                               const std::string& where, bool quantized) {
  // glTF 2.0 3.7.2.2, widened by KHR_mesh_quantization: displacements may be signed integers,
  // normalised or (positions only) not.
  std::vector<Format> position_formats = {{kFloat, false}}, normal_formats = {{kFloat, false}};
  if (quantized) {
    position_formats.insert(position_formats.end(), {{kByte, false}, {kByte, true}, {kShort, false}, {kShort, true}});
    normal_formats.insert(normal_formats.end(), {{kByte, true}, {kShort, true}});
  }
  Mesh::Morph morph;
  for (size_t t = 0; t < primitive.targets.size(); ++t) {
    const std::string field = where + ".targets[" + std::to_string(t) + "]";
    auto read = [&](const char* name, const std::vector<Format>& formats) {
      std::vector<glm::vec3> moved;
      const auto found = primitive.targets[t].find(name);
      if (found == primitive.targets[t].end()) return moved;
      moved = read_floats<3>(document, found->second, field + "." + name, formats);
      if (moved.size() != vertex_count)
        fail(field + "." + name + ": count " + std::to_string(moved.size()) + " differs from POSITION's " +
             std::to_string(vertex_count));
      return moved;
    };
    morph.positions.push_back(read("POSITION", position_formats));
    morph.normals.push_back(read("NORMAL", normal_formats));
  }
  morph.weights.assign(primitive.targets.size(), 0.0f);
  return morph;
}

std::vector<float> default_weights(const tinygltf::Model& model, int node_index, size_t target_count) {
  const tinygltf::Node& node = model.nodes[static_cast<size_t>(node_index)];
  const tinygltf::Mesh& mesh = model.meshes[static_cast<size_t>(node.mesh)];
  const std::vector<double>* given = nullptr;
  std::string field;
  if (!node.weights.empty()) {
    given = &node.weights;
    field = "nodes[" + std::to_string(node_index) + "].weights";
  } else if (!mesh.weights.empty()) {
    given = &mesh.weights;
    field = "meshes[" + std::to_string(node.mesh) + "].weights";
  }
  std::vector<float> weights(target_count, 0.0f);
  if (!given) return weights;
  if (given->size() != target_count)
    fail(field + ": " + std::to_string(given->size()) + " weights; expected one per morph target (" +
         std::to_string(target_count) + ")");
  for (size_t i = 0; i < target_count; ++i) {
    if (!std::isfinite((*given)[i]) || std::abs((*given)[i]) > 3e38)
      fail(field + ": element " + std::to_string(i) + " is not a finite number");
    weights[i] = static_cast<float>((*given)[i]);
  }
  return weights;
}

void settle_morphs(Scene& scene, const Rig& rig) {
  // Per node, each weight's lowest and highest value over its rest weight and every key.
  std::vector<std::vector<float>> low(rig.nodes.size()), high(rig.nodes.size());
  std::vector<char> animated(rig.nodes.size(), 0);
  for (size_t n = 0; n < rig.nodes.size(); ++n) low[n] = high[n] = rig.nodes[n].weights;
  for (const Animation& animation : rig.animations)
    for (const AnimationChannel& channel : animation.channels) {
      if (channel.property != AnimatedProperty::weights) continue;
      const auto node = static_cast<size_t>(channel.node);
      animated[node] = 1;
      const bool cubic = channel.interpolation == Interpolation::cubic_spline;
      for (size_t i = 0; i < channel.weights.size(); ++i) {
        // A cubic spline's tangents are not values; between its keys it may overshoot them a
        // little, which the box does not hold.
        if (cubic && (i / channel.width) % 3 != 1) continue;
        const size_t w = i % channel.width;
        low[node][w] = std::min(low[node][w], channel.weights[i]);
        high[node][w] = std::max(high[node][w], channel.weights[i]);
      }
    }
  for (const Instance& instance : scene.instances) {
    Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    Mesh::Morph& morph = mesh.morph;
    if (morph.target_count() == 0) continue;
    if (instance.node < 0 || !animated[static_cast<size_t>(instance.node)]) {
      morph = Mesh::Morph();
      continue;
    }
    const auto node = static_cast<size_t>(instance.node);
    mesh.min = glm::vec3(std::numeric_limits<float>::max());
    mesh.max = glm::vec3(std::numeric_limits<float>::lowest());
    for (size_t i = 0; i < mesh.vertices.size(); ++i) {
      glm::vec3 lo = mesh.vertices[i].position, hi = lo;
      for (size_t t = 0; t < morph.target_count(); ++t) {
        if (morph.positions[t].empty()) continue;
        const glm::vec3 a = (low[node][t] - morph.weights[t]) * morph.positions[t][i];
        const glm::vec3 b = (high[node][t] - morph.weights[t]) * morph.positions[t][i];
        lo += glm::min(a, b);
        hi += glm::max(a, b);
      }
      mesh.min = glm::min(mesh.min, lo);
      mesh.max = glm::max(mesh.max, hi);
    }
  }
}

}  // namespace scene::gltf
