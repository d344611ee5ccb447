#include "gltf_builder.h"

#include "gltf_accessors.h"
#include "gltf_animation.h"
#include "gltf_document.h"
#include "gltf_draco.h"
#include "gltf_lights.h"
#include "gltf_materials.h"
#include "gltf_morph.h"
#include "gltf_skin.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>

namespace scene::gltf {
namespace {

constexpr int kFloat = TINYGLTF_COMPONENT_TYPE_FLOAT, kByte = TINYGLTF_COMPONENT_TYPE_BYTE,
              kUnsignedByte = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, kShort = TINYGLTF_COMPONENT_TYPE_SHORT,
              kUnsignedShort = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, kUnsignedInt = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;

// Extensions whose content the player reads; any of them may be listed in extensionsRequired.
const std::set<std::string> kSupportedExtensions = {
    "KHR_mesh_quantization", "EXT_meshopt_compression",         "KHR_draco_mesh_compression", "KHR_texture_transform",
    "KHR_materials_unlit",   "KHR_materials_emissive_strength", "KHR_lights_punctual"};

// What a scene using an extension the player does not read shows instead.
std::string shown_instead(const std::string& extension) {
  if (extension == "KHR_texture_basisu" || extension == "EXT_texture_webp" || extension == "MSFT_texture_dds")
    return "textures whose only source is in that format are drawn white";
  if (extension.rfind("KHR_materials_", 0) == 0) return "materials show their core glTF properties";
  return "the file's core glTF content is shown";
}

// The formats glTF 2.0 (3.7.2.1) allows for each attribute the player reads, widened by
// KHR_mesh_quantization when the file uses it.
std::vector<Format> position_formats(bool quantized) {
  if (!quantized) return {{kFloat, false}};
  return {{kFloat, false}, {kByte, false}, {kByte, true},           {kUnsignedByte, false}, {kUnsignedByte, true},
          {kShort, false}, {kShort, true}, {kUnsignedShort, false}, {kUnsignedShort, true}};
}
std::vector<Format> normal_formats(bool quantized) {
  if (!quantized) return {{kFloat, false}};
  return {{kFloat, false}, {kByte, true}, {kShort, true}};
}
std::vector<Format> tangent_formats(bool quantized) {
  return normal_formats(quantized);
}
std::vector<Format> texcoord_formats(bool quantized) {
  if (!quantized) return {{kFloat, false}, {kUnsignedByte, true}, {kUnsignedShort, true}};
  return position_formats(true);
}

class Builder {
 public:
  Builder(Document& document, const LightReader& lights, LoadReport& report)
      : document_(document),
        lights_(lights),
        model_(document.model()),
        report_(report),
        quantized_(document.uses_extension("KHR_mesh_quantization")) {}

  Scene build(const std::string& name) {
    scene_.name = name;
    for (const std::string& extension : model_.extensionsRequired)
      if (!kSupportedExtensions.count(extension)) fail("extensionsRequired: '" + extension + "' is not supported by this player");
    for (const std::string& extension : model_.extensionsUsed)
      if (!kSupportedExtensions.count(extension))
        report_.warnings.push_back("extensionsUsed: '" + extension + "' is not supported; " + shown_instead(extension));
    const tinygltf::Scene* shown = nullptr;
    int shown_index = 0;
    if (!model_.scenes.empty()) {
      const int index = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (static_cast<size_t>(index) >= model_.scenes.size())
        fail("scene: " + std::to_string(index) + " out of range (there are " + std::to_string(model_.scenes.size()) + ")");
      shown = &model_.scenes[static_cast<size_t>(index)];
      shown_index = index;
    }
    // glTF allows a file without scenes ("nothing to render at load time", 3.5.1): the kiosk has
    // nothing it could rightly choose to show, so it says so rather than guessing at root nodes.
    if (!shown || shown->nodes.empty()) fail("scenes: the file has no scene with nodes to show");
    // Only a file that animates or skins keeps its node tree: a static scene needs its instances alone.
    if (!model_.animations.empty() || !model_.skins.empty()) {
      rig_ = std::make_shared<Rig>();
      node_of_.assign(model_.nodes.size(), -1);
    }
    visit(shown->nodes, "scenes[" + std::to_string(shown_index) + "].nodes");
    if (rig_) {
      rig_->animations = read_animations(document_, node_of_, *rig_);
      settle_morphs(scene_, *rig_);
      rig_->skins = read_skins(document_, node_of_);
      place_skinned();
      scene_.rig = std::move(rig_);
    }
    if (scene_.instances.empty()) fail("meshes: the scene contains no triangles to render");
    update_bounds(scene_);
    if (!std::isfinite(scene_.bounds.radius()))
      fail("nodes: the transformed scene bounds are not finite (a transform overflows)");
    return std::move(scene_);
  }

 private:
  // The node's own transform as the file gives it, checked finite.
  static Rig::Node rest_node(const tinygltf::Node& node, const std::string& where) {
    auto check = [&](const std::vector<double>& values, const char* field) {
      for (double value : values)
        if (!std::isfinite(value)) fail(where + "." + field + ": expected finite numbers");
    };
    check(node.matrix, "matrix");
    check(node.translation, "translation");
    check(node.rotation, "rotation");
    check(node.scale, "scale");
    Rig::Node out;
    if (node.matrix.size() == 16) {
      out.uses_matrix = true;
      out.matrix = glm::make_mat4(node.matrix.data());
    }
    if (node.translation.size() == 3) out.translation = glm::make_vec3(node.translation.data());
    if (node.rotation.size() == 4)
      out.rotation = glm::normalize(glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]));
    if (node.scale.size() == 3) out.scale = glm::make_vec3(node.scale.data());
    return out;
  }

  // Depth-first over the node tree with an explicit stack: a valid file may chain 100,000 nodes,
  // far deeper than the thread's stack allows recursion. on_path marks the nodes from the root to
  // the current one (a child among them is a cycle), seen every node entered (a second entry is a
  // second parent); both are flags per node, so a deep chain costs linear time.
  void visit(const std::vector<int>& roots, const std::string& roots_field) {
    struct OpenNode {
      int node;
      glm::dmat4 world;
      size_t next_child;
      int rig_node;  // -1 without a rig
    };
    std::vector<OpenNode> stack;
    std::vector<char> on_path(model_.nodes.size(), 0), seen(model_.nodes.size(), 0);
    auto enter = [&](int index, const glm::dmat4& parent, int rig_parent, const std::string& field) {
      if (index < 0 || static_cast<size_t>(index) >= model_.nodes.size())
        fail(field + ": node index " + std::to_string(index) + " out of range (there are " + std::to_string(model_.nodes.size()) +
             ")");
      const size_t at = static_cast<size_t>(index);
      if (on_path[at]) fail("nodes[" + std::to_string(index) + "].children: the node hierarchy has a cycle through this node");
      if (seen[at]) fail("nodes[" + std::to_string(index) + "]: the node has more than one parent (glTF requires a tree)");
      seen[at] = on_path[at] = 1;
      const std::string where = "nodes[" + std::to_string(index) + "]";
      const tinygltf::Node& node = model_.nodes[at];
      Rig::Node local = rest_node(node, where);
      if (node.mesh >= 0 && static_cast<size_t>(node.mesh) >= model_.meshes.size())
        fail(where + ".mesh: " + std::to_string(node.mesh) + " out of range (there are " + std::to_string(model_.meshes.size()) +
             ")");
      const size_t targets = node.mesh >= 0 ? target_count(model_.meshes[static_cast<size_t>(node.mesh)],
                                                           "meshes[" + std::to_string(node.mesh) + "]")
                                            : 0;
      std::vector<float> weights;
      if (targets > 0) weights = default_weights(model_, index, targets);
      if (rig_) local.weights = weights;
      const glm::dmat4 world = parent * local.local();
      const int rig_node = rig_ ? add_rig_node(std::move(local), rig_parent) : -1;
      if (rig_) node_of_[at] = rig_node;
      if (node.camera >= 0) {
        scene_.cameras.push_back(file_camera(node.camera, world, index));
        scene_.cameras.back().rig_node = rig_node;
      }
      if (auto light = lights_.place(document_.root().at("nodes").at(at), index, world)) {
        light->rig_node = rig_node;
        add_light(*light);
      }
      if (node.skin >= 0 && static_cast<size_t>(node.skin) >= model_.skins.size())
        fail(where + ".skin: " + std::to_string(node.skin) + " out of range (there are " + std::to_string(model_.skins.size()) +
             ")");
      const int skin = node.mesh >= 0 ? node.skin : -1;
      if (node.mesh >= 0)
        for (int mesh : meshes_of(node.mesh, weights, skin)) {
          const bool skinned = !scene_.meshes[static_cast<size_t>(mesh)].joints.empty();
          scene_.instances.push_back({mesh, world, rig_node, glm::dmat4(1.0), skinned ? skin : -1, {}});
        }
      stack.push_back({index, world, 0, rig_node});
    };
    for (size_t r = 0; r < roots.size(); ++r) {
      enter(roots[r], glm::dmat4(1.0), -1, roots_field + "[" + std::to_string(r) + "]");
      while (!stack.empty()) {
        OpenNode& top = stack.back();
        const std::vector<int>& children = model_.nodes[static_cast<size_t>(top.node)].children;
        if (top.next_child == children.size()) {
          on_path[static_cast<size_t>(top.node)] = 0;
          stack.pop_back();
          continue;
        }
        const size_t c = top.next_child++;
        const glm::dmat4 parent = top.world;  // enter() grows the stack, which may move `top`
        const int rig_parent = top.rig_node;
        enter(children[c], parent, rig_parent, "nodes[" + std::to_string(top.node) + "].children[" + std::to_string(c) + "]");
      }
    }
  }

  int add_rig_node(Rig::Node node, int parent) {
    node.parent = parent;
    rig_->nodes.push_back(std::move(node));
    return static_cast<int>(rig_->nodes.size()) - 1;
  }

  void add_light(const Light& light) {
    if (scene_.lights.size() < kMaxLights) {
      scene_.lights.push_back(light);
      return;
    }
    if (lights_left_out_++ == 0)
      report_.warnings.push_back("nodes[" + std::to_string(light.node) + "].extensions.KHR_lights_punctual: more than " +
                                 std::to_string(kMaxLights) + " lights; the first " + std::to_string(kMaxLights) +
                                 " in node order are shown");
  }

  // glTF 2.0, 5.13: perspective with yfov > 0, znear > 0 and zfar absent or beyond znear;
  // orthographic with non-zero magnifications and zfar beyond znear >= 0.
  FileCamera file_camera(int index, const glm::dmat4& world, int node) {
    const std::string field = "cameras[" + std::to_string(index) + "]";
    if (static_cast<size_t>(index) >= model_.cameras.size())
      fail("nodes[" + std::to_string(node) + "].camera: " + std::to_string(index) + " out of range (there are " +
           std::to_string(model_.cameras.size()) + ")");
    const tinygltf::Camera& source = model_.cameras[static_cast<size_t>(index)];
    FileCamera camera;
    camera.node = node;
    place_camera(camera, world);
    if (source.type == "perspective") {
      const tinygltf::PerspectiveCamera& p = source.perspective;
      if (!std::isfinite(p.yfov) || p.yfov <= 0.0 || p.yfov >= 3.14159)
        fail(field + ".perspective.yfov: " + std::to_string(p.yfov) + "; expected radians in (0, pi)");
      if (!std::isfinite(p.znear) || p.znear <= 0.0)
        fail(field + ".perspective.znear: " + std::to_string(p.znear) + "; expected a distance > 0");
      if (!std::isfinite(p.zfar) || (p.zfar != 0.0 && p.zfar <= p.znear))
        fail(field + ".perspective.zfar: " + std::to_string(p.zfar) + "; expected a distance beyond znear, or none");
      camera.yfov = p.yfov;
      camera.znear = p.znear;
      camera.zfar = p.zfar;
    } else if (source.type == "orthographic") {
      const tinygltf::OrthographicCamera& o = source.orthographic;
      if (!std::isfinite(o.xmag) || !std::isfinite(o.ymag) || o.xmag == 0.0 || o.ymag == 0.0)
        fail(field + ".orthographic: xmag and ymag must be finite and non-zero");
      if (!std::isfinite(o.znear) || !std::isfinite(o.zfar) || o.znear < 0.0 || o.zfar <= o.znear)
        fail(field + ".orthographic: expected 0 <= znear < zfar");
      camera.perspective = false;
      camera.znear = o.znear;
      camera.zfar = o.zfar;
    } else {
      fail(field + ".type: \"" + source.type + "\"; expected \"perspective\" or \"orthographic\"");
    }
    return camera;
  }

  // The Scene meshes of glTF mesh `index`, one per triangle primitive, converted once and shared by
  // instances; a mesh with morph targets, shaped at `weights`, is converted for each node that shows
  // it, as the nodes may give it different weights, and so is one that `skin` (>= 0) deforms.
  std::vector<int> meshes_of(int index, const std::vector<float>& weights, int skin) {
    const bool shared = weights.empty() && skin < 0;
    if (shared)
      if (auto found = converted_.find(index); found != converted_.end()) return found->second;
    std::vector<int> ids;
    const tinygltf::Mesh& mesh = model_.meshes[static_cast<size_t>(index)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const std::string where = "meshes[" + std::to_string(index) + "].primitives[" + std::to_string(p) + "]";
      const tinygltf::Primitive& primitive = mesh.primitives[p];
      if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
          primitive.mode != TINYGLTF_MODE_TRIANGLE_FAN && primitive.mode != -1) {
        report_.warnings.push_back(where + ": mode " + std::to_string(primitive.mode) + " is not triangles; skipped");
        continue;
      }
      const nlohmann::json& source = document_.root()["meshes"][static_cast<size_t>(index)]["primitives"][p];
      Mesh converted = convert(primitive, source, where, weights, skin);
      if (converted.indices.empty()) continue;
      scene_.meshes.push_back(std::move(converted));
      ids.push_back(static_cast<int>(scene_.meshes.size()) - 1);
    }
    if (shared) converted_[index] = ids;
    return ids;
  }

  // Each skinned instance at the rest pose: its skin's matrices, and its draws anchored at the
  // skin's first joint. A skin a shown mesh uses must have every joint in the shown scene.
  void place_skinned() {
    std::vector<glm::dmat4> worlds(rig_->nodes.size());
    for (size_t i = 0; i < rig_->nodes.size(); ++i) {
      const Rig::Node& node = rig_->nodes[i];
      worlds[i] = node.parent < 0 ? node.local() : worlds[static_cast<size_t>(node.parent)] * node.local();
    }
    for (Instance& instance : scene_.instances) {
      if (instance.skin < 0) continue;
      const Rig::Skin& skin = rig_->skins[static_cast<size_t>(instance.skin)];
      for (size_t j = 0; j < skin.joints.size(); ++j)
        if (skin.joints[j] < 0)
          fail("skins[" + std::to_string(instance.skin) + "].joints[" + std::to_string(j) + "]: node " +
               std::to_string(model_.skins[static_cast<size_t>(instance.skin)].joints[j]) +
               " is not in the shown scene; expected the joints of a shown skin there");
      skin_matrices(skin, worlds, instance.skin_matrices);
      instance.world = worlds[static_cast<size_t>(skin.joints[0])];
    }
  }

  // Attribute `name` of a primitive, from its Draco mesh when the extension compresses it, else
  // from its accessor.
  template <int N>
  std::vector<glm::vec<N, float>> attribute(const DracoPrimitive* draco, const std::string& name, int accessor,
                                            const std::string& field, const std::vector<Format>& formats) {
    if (draco)
      if (const auto found = draco->attributes.find(name); found != draco->attributes.end()) {
        if (draco->components.at(name) != N)
          fail(field + ": expected " + std::to_string(N) + " components per element, got " +
               std::to_string(draco->components.at(name)));
        std::vector<glm::vec<N, float>> values(draco->points);
        for (size_t i = 0; i < draco->points; ++i)
          for (int c = 0; c < N; ++c) {
            const float value = found->second[i * N + static_cast<size_t>(c)];
            if (!std::isfinite(value))
              fail(field + ": decoded element " + std::to_string(i) + " component " + std::to_string(c) +
                   " is not a finite number");
            values[i][c] = value;
          }
        return values;
      }
    return read_floats<N>(document_, accessor, field, formats);
  }

  // The primitive's TEXCOORD_<mapping.set>, transformed; empty when it has none (then a warning
  // if a texture reads it: `needed`).
  std::vector<glm::vec2> mapped_uvs(const DracoPrimitive* decoded, const tinygltf::Primitive& primitive, const UvMapping& mapping,
                                    size_t vertex_count, const std::string& where, bool needed) {
    const std::string uv_name = "TEXCOORD_" + std::to_string(mapping.set);
    std::vector<glm::vec2> uvs;
    const auto at = primitive.attributes.find(uv_name);
    if (at == primitive.attributes.end()) {
      if (needed && mapping.set != 0)
        report_.warnings.push_back(where + ".attributes: the material's textures read " + uv_name +
                                   ", which the primitive lacks; they are sampled at (0, 0)");
      return uvs;
    }
    uvs = attribute<2>(decoded, uv_name, at->second, where + ".attributes." + uv_name, texcoord_formats(quantized_));
    if (uvs.size() != vertex_count) fail(where + ".attributes." + uv_name + ": count differs from POSITION's");
    if (mapping.transformed)
      for (glm::vec2& uv : uvs) {
        const glm::dvec3 moved = mapping.transform * glm::dvec3(uv, 1.0);
        if (!std::isfinite(moved.x) || !std::isfinite(moved.y) || std::abs(moved.x) > 3e38 || std::abs(moved.y) > 3e38)
          fail(where + ".attributes." + uv_name + ": KHR_texture_transform takes a coordinate beyond the float range");
        uv = glm::vec2(moved);
      }
    return uvs;
  }

  // The primitive's morph targets, with `positions` and `normals` moved to the shape `weights`
  // give; empty where it has none or they cannot be read (a Draco primitive's: its points are
  // reordered).
  Mesh::Morph shape(const tinygltf::Primitive& primitive, const DracoPrimitive* decoded, const std::vector<float>& weights,
                    std::vector<glm::vec3>& positions, std::vector<glm::vec3>& normals, const std::string& where) {
    if (primitive.targets.empty() || weights.size() != primitive.targets.size()) return {};
    if (decoded) {
      report_.warnings.push_back(where +
                                 ".targets: morph targets of a Draco-compressed primitive are not read; it is shown in "
                                 "its base shape");
      return {};
    }
    Mesh::Morph morph = read_morph_targets(document_, primitive, positions.size(), where, quantized_);
    if (std::any_of(primitive.targets.begin(), primitive.targets.end(), [](const auto& t) { return t.count("TANGENT") > 0; }))
      report_.warnings.push_back(where +
                                 ".targets: TANGENT displacements are not applied; a normal map turns with the "
                                 "base tangents, made orthogonal to the morphed normal");
    morph.weights = weights;
    morph.base_normals = normals;
    for (size_t t = 0; t < weights.size(); ++t) {
      if (weights[t] == 0.0f) continue;
      if (!morph.positions[t].empty())
        for (size_t i = 0; i < positions.size(); ++i) positions[i] += weights[t] * morph.positions[t][i];
      if (!morph.normals[t].empty() && !normals.empty())
        for (size_t i = 0; i < normals.size(); ++i) normals[i] += weights[t] * morph.normals[t][i];
    }
    for (const glm::vec3& p : positions)
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
        fail(where + ".targets: the weighted displacements take a position beyond the float range");
    return morph;
  }

  // JOINTS_0 and WEIGHTS_0 of a primitive `skin` deforms (none: it is drawn unskinned, with a
  // warning); a second set of four influences is left out with a warning.
  void read_skinning(const tinygltf::Primitive& primitive, const DracoPrimitive* decoded, int skin, size_t vertex_count,
                     const std::string& where, std::vector<glm::vec<4, uint16_t>>& joints, std::vector<glm::vec4>& weights) {
    const auto joints_at = primitive.attributes.find("JOINTS_0"), weights_at = primitive.attributes.find("WEIGHTS_0");
    if (joints_at == primitive.attributes.end() || weights_at == primitive.attributes.end()) {
      report_.warnings.push_back(where + ".attributes: its node has a skin but it lacks JOINTS_0 or WEIGHTS_0; drawn unskinned");
      return;
    }
    if (primitive.attributes.count("JOINTS_1"))
      report_.warnings.push_back(where +
                                 ".attributes: JOINTS_1 and WEIGHTS_1 are not read; each vertex follows its first "
                                 "four joints");
    const auto indices = attribute<4>(decoded, "JOINTS_0", joints_at->second, where + ".attributes.JOINTS_0",
                                      {{kUnsignedByte, false}, {kUnsignedShort, false}});
    weights = attribute<4>(decoded, "WEIGHTS_0", weights_at->second, where + ".attributes.WEIGHTS_0",
                           {{kFloat, false}, {kUnsignedByte, true}, {kUnsignedShort, true}});
    if (indices.size() != vertex_count || weights.size() != vertex_count)
      fail(where + ".attributes: JOINTS_0 and WEIGHTS_0 must have as many elements as POSITION");
    check_skin_attributes(indices, weights, model_.skins[static_cast<size_t>(skin)].joints.size(), where, joints);
  }

  Mesh convert(const tinygltf::Primitive& primitive, const nlohmann::json& source, const std::string& where,
               const std::vector<float>& weights, int skin) {
    std::optional<DracoPrimitive> draco;
    if (const auto extensions = source.find("extensions"); extensions != source.end() && extensions->is_object())
      if (const auto compressed = extensions->find("KHR_draco_mesh_compression"); compressed != extensions->end()) {
        if (primitive.mode != TINYGLTF_MODE_TRIANGLES && primitive.mode != -1)
          fail(where + ".mode: " + std::to_string(primitive.mode) +
               "; KHR_draco_mesh_compression holds a triangle list, expected mode 4");
        draco = decode_draco(document_, *compressed, primitive.attributes, primitive.indices, where);
      }
    const DracoPrimitive* decoded = draco ? &*draco : nullptr;
    const auto position_at = primitive.attributes.find("POSITION");
    if (position_at == primitive.attributes.end()) fail(where + ".attributes: POSITION is required");
    auto positions =
        attribute<3>(decoded, "POSITION", position_at->second, where + ".attributes.POSITION", position_formats(quantized_));
    const size_t vertex_count = positions.size();
    // decode_draco checks its indices against its own points, so the vertices must be those points
    // even when POSITION itself was not compressed.
    if (decoded && decoded->points != vertex_count)
      fail(where + ".attributes.POSITION: " + std::to_string(vertex_count) + " vertices, but the Draco mesh has " +
           std::to_string(decoded->points) + " points; expected the same count");

    // glTF 2.0, 3.7.2.1: all attribute accessors of a primitive have the same count; checked for the
    // attributes the player does not read as well, as Khronos' validator does.
    for (const auto& [name, accessor] : primitive.attributes)
      if (accessor >= 0 && static_cast<size_t>(accessor) < model_.accessors.size() &&
          model_.accessors[static_cast<size_t>(accessor)].count != vertex_count)
        fail(where + ".attributes." + name + ": count " + std::to_string(model_.accessors[static_cast<size_t>(accessor)].count) +
             " differs from POSITION's " + std::to_string(vertex_count));

    std::vector<glm::vec3> normals;
    if (auto at = primitive.attributes.find("NORMAL"); at != primitive.attributes.end()) {
      normals = attribute<3>(decoded, "NORMAL", at->second, where + ".attributes.NORMAL", normal_formats(quantized_));
      if (normals.size() != vertex_count) fail(where + ".attributes.NORMAL: count differs from POSITION's");
    }
    Mesh::Morph morph = shape(primitive, decoded, weights, positions, normals, where);
    std::vector<glm::vec<4, uint16_t>> joints;
    std::vector<glm::vec4> joint_weights;
    if (skin >= 0) read_skinning(primitive, decoded, skin, vertex_count, where, joints, joint_weights);
    // Only an animated file can change the weights (settle_morphs drops what no channel moves).
    if (!rig_) morph = Mesh::Morph();
    const int material_id = materials_.material(primitive.material, where);
    const MaterialMappings& mappings = materials_.mappings(material_id);
    const scene::Material& shown = scene_.materials[static_cast<size_t>(material_id)];
    const std::vector<glm::vec2> uvs = mapped_uvs(decoded, primitive, mappings.first, vertex_count, where, mappings.has_first);
    std::vector<glm::vec2> second_uvs;
    if (mappings.has_second) second_uvs = mapped_uvs(decoded, primitive, mappings.second, vertex_count, where, true);
    // A set the primitive lacks is sampled at (0, 0), as the warning says; the stream must still be
    // as long as the vertices (tangents may be generated from it).
    if (mappings.has_second && second_uvs.empty()) second_uvs.assign(vertex_count, glm::vec2(0.0f));
    std::vector<glm::vec4> tangents;
    const bool wants_tangents = shown.normal.present() && !normals.empty();
    if (auto at = primitive.attributes.find("TANGENT"); wants_tangents && at != primitive.attributes.end()) {
      tangents = attribute<4>(decoded, "TANGENT", at->second, where + ".attributes.TANGENT", tangent_formats(quantized_));
      if (tangents.size() != vertex_count) fail(where + ".attributes.TANGENT: count differs from POSITION's");
    }

    std::vector<uint32_t> indices;
    if (decoded) {
      indices = draco->indices;  // decode_draco has checked every index against the points
    } else if (primitive.indices >= 0) {
      read_accessor(
          document_, primitive.indices, where + ".indices",
          {{kUnsignedByte, false}, {kUnsignedShort, false}, {kUnsignedInt, false}}, 1,
          [&](size_t count) { indices.resize(count); },
          [&](size_t i, const double* value) {
            if (*value >= static_cast<double>(vertex_count))
              fail(where + ".indices: element " + std::to_string(i) + " is " + std::to_string(static_cast<uint64_t>(*value)) +
                   ", expected less than the vertex count " + std::to_string(vertex_count));
            indices[i] = static_cast<uint32_t>(*value);
          });
    } else {
      indices.resize(vertex_count);
      for (size_t i = 0; i < vertex_count; ++i) indices[i] = static_cast<uint32_t>(i);
    }
    indices = to_triangle_list(indices, primitive.mode);

    Mesh mesh;
    mesh.material = material_id;
    if (normals.empty()) {
      // The spec: without NORMAL, flat normals. Each triangle gets its own three vertices.
      mesh.vertices.reserve(indices.size());
      for (uint32_t from : indices)
        if (!joints.empty()) {
          mesh.joints.push_back(joints[from]);
          mesh.joint_weights.push_back(joint_weights[from]);
        }
      Mesh::Morph per_corner = morph;
      for (size_t t = 0; t < morph.target_count(); ++t) {
        per_corner.positions[t].clear();
        per_corner.normals[t].clear();
        if (!morph.positions[t].empty())
          for (uint32_t from : indices) per_corner.positions[t].push_back(morph.positions[t][from]);
      }
      mesh.morph = std::move(per_corner);
      for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const glm::vec3 a = positions[indices[t]], b = positions[indices[t + 1]], c = positions[indices[t + 2]];
        const glm::dvec3 cross = glm::cross(glm::dvec3(b - a), glm::dvec3(c - a));
        const double length = glm::length(cross);
        const glm::vec3 normal = length > 0.0 && std::isfinite(length) ? glm::vec3(cross / length) : glm::vec3(0.0f);
        for (int k = 0; k < 3; ++k) {
          const uint32_t from = indices[t + static_cast<size_t>(k)];
          mesh.vertices.push_back({positions[from], normal, uvs.empty() ? glm::vec2(0.0f) : uvs[from]});
          if (!second_uvs.empty()) mesh.uv1.push_back(second_uvs[from]);
          mesh.indices.push_back(static_cast<uint32_t>(mesh.vertices.size() - 1));
        }
      }
    } else {
      mesh.vertices.resize(vertex_count);
      for (size_t i = 0; i < vertex_count; ++i) {
        const float length = glm::length(normals[i]);
        // Non-unit normals are normalised; zero ones stay zero and the shader faces them to the eye.
        const glm::vec3 normal = length > 1e-30f && std::isfinite(length) ? normals[i] / length : glm::vec3(0.0f);
        mesh.vertices[i] = {positions[i], normal, uvs.empty() ? glm::vec2(0.0f) : uvs[i]};
      }
      mesh.indices = std::move(indices);
      mesh.uv1 = std::move(second_uvs);
      mesh.morph = std::move(morph);
      mesh.joints = std::move(joints);
      mesh.joint_weights = std::move(joint_weights);
      // The file's tangents, normalised; w must be the sign of a handedness (glTF: +1 or -1).
      for (size_t i = 0; i < tangents.size(); ++i) {
        glm::vec4& t = tangents[i];
        const float length = glm::length(glm::vec3(t));
        if (!(length > 1e-30f)) {
          tangents.clear();  // a zero tangent: the file's frames are unusable, so all are generated
          report_.warnings.push_back(where + ".attributes.TANGENT: element " + std::to_string(i) +
                                     " is zero; tangents are generated instead");
          break;
        }
        t = glm::vec4(glm::vec3(t) / length, t.w < 0.0f ? -1.0f : 1.0f);
      }
      mesh.tangents = std::move(tangents);
    }
    if (shown.normal.present() && mesh.tangents.empty()) generate_tangents(mesh, shown.normal.second_uv);
    mesh.min = glm::vec3(std::numeric_limits<float>::max());
    mesh.max = glm::vec3(std::numeric_limits<float>::lowest());
    for (const Vertex& v : mesh.vertices) {
      mesh.min = glm::min(mesh.min, v.position);
      mesh.max = glm::max(mesh.max, v.position);
    }
    return mesh;
  }

  static std::vector<uint32_t> to_triangle_list(const std::vector<uint32_t>& in, int mode) {
    std::vector<uint32_t> out;
    // glTF 2.0, 3.7.2.1: strip triangle i is {v_i, v_(i+1+i%2), v_(i+2-i%2)} (every other one flipped
    // back to counter-clockwise), fan triangle i is {v_(i+1), v_(i+2), v_0}; kept in exactly that order.
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (size_t i = 0; i + 2 < in.size(); ++i) out.insert(out.end(), {in[i], in[i + 1 + i % 2], in[i + 2 - i % 2]});
    } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
      for (size_t i = 0; i + 2 < in.size(); ++i) out.insert(out.end(), {in[i + 1], in[i + 2], in[0]});
    } else {
      out.assign(in.begin(), in.begin() + static_cast<std::ptrdiff_t>(in.size() / 3 * 3));
    }
    return out;
  }

  Document& document_;
  const LightReader& lights_;
  const tinygltf::Model& model_;
  LoadReport& report_;
  const bool quantized_;
  Scene scene_;
  std::map<int, std::vector<int>> converted_;
  size_t lights_left_out_ = 0;                            // warned of once
  std::shared_ptr<Rig> rig_;                              // while the nodes are visited, in an animated file
  std::vector<int> node_of_;                              // file node -> rig node
  MaterialReader materials_{document_, scene_, report_};  // after scene_: it adds the default material
};

}  // namespace

Scene build_scene(Document& document, const LightReader& lights, LoadReport& report, const std::string& name) {
  return Builder(document, lights, report).build(name);
}

}  // namespace scene::gltf
