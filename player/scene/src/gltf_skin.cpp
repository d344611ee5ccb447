#include "gltf_skin.h"

#include "gltf_accessors.h"
#include "gltf_document.h"

#include <glm/gtc/type_ptr.hpp>

#include <cmath>

namespace scene::gltf {

std::vector<Rig::Skin> read_skins(Document& document, const std::vector<int>& node_of) {
  const tinygltf::Model& model = document.model();
  std::vector<Rig::Skin> skins;
  for (size_t s = 0; s < model.skins.size(); ++s) {
    const tinygltf::Skin& source = model.skins[s];
    const std::string where = "skins[" + std::to_string(s) + "]";
    Rig::Skin skin;
    if (source.joints.empty()) fail(where + ".joints: expected at least one joint");
    for (size_t j = 0; j < source.joints.size(); ++j) {
      const int node = source.joints[j];
      if (node < 0 || static_cast<size_t>(node) >= model.nodes.size())
        fail(where + ".joints[" + std::to_string(j) + "]: node " + std::to_string(node) + " out of range (there are " +
             std::to_string(model.nodes.size()) + ")");
      // A joint outside the shown scene has no place to give its vertices; a skin no shown mesh
      // uses is kept all the same (its joints are then checked only for their index).
      skin.joints.push_back(node_of[static_cast<size_t>(node)]);
    }
    skin.inverse_bind.assign(skin.joints.size(), glm::dmat4(1.0));
    if (source.inverseBindMatrices >= 0) {
      const std::string field = where + ".inverseBindMatrices";
      size_t count = 0;
      read_accessor(
          document, source.inverseBindMatrices, field, {{TINYGLTF_COMPONENT_TYPE_FLOAT, false}}, 16,
          [&](size_t elements) {
            count = elements;
            if (count != skin.joints.size())
              fail(field + ": " + std::to_string(count) + " matrices for " + std::to_string(skin.joints.size()) +
                   " joints; expected one per joint");
          },
          [&](size_t i, const double* values) {
            for (int c = 0; c < 16; ++c)
              if (!std::isfinite(values[c]) || std::abs(values[c]) > 3e38)
                fail(field + ": matrix " + std::to_string(i) + " element " + std::to_string(c) + " is not a finite number");
            skin.inverse_bind[i] = glm::make_mat4(values);
          });
    }
    skins.push_back(std::move(skin));
  }
  return skins;
}

void check_skin_attributes(const std::vector<glm::vec4>& joints, std::vector<glm::vec4>& weights, size_t joint_count,
                           const std::string& where, std::vector<glm::vec<4, uint16_t>>& joints_out) {
  joints_out.resize(joints.size());
  for (size_t i = 0; i < joints.size(); ++i) {
    float sum = 0.0f;
    for (int k = 0; k < 4; ++k) {
      if (weights[i][k] < 0.0f)
        fail(where + ".attributes.WEIGHTS_0: element " + std::to_string(i) + " has a negative weight; expected weights >= 0");
      // An unweighted influence may name any joint (exporters pad with 0); it moves nothing.
      const double joint = weights[i][k] > 0.0f ? joints[i][k] : 0.0;
      if (joint >= static_cast<double>(joint_count))
        fail(where + ".attributes.JOINTS_0: element " + std::to_string(i) + " names joint " +
             std::to_string(static_cast<uint64_t>(joint)) + ", expected less than the skin's " + std::to_string(joint_count) +
             " joints");
      joints_out[i][k] = static_cast<uint16_t>(joint);
      sum += weights[i][k];
    }
    weights[i] = sum > 0.0f ? weights[i] / sum : glm::vec4(1, 0, 0, 0);
  }
}

}  // namespace scene::gltf
