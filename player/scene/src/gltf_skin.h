#pragma once
// glTF skins (3.7.3): each skin's joints, as nodes of the rig (`node_of` maps a file node to the
// rig's, -1 where the shown scene does not hold it), and their inverse bind matrices (identity
// without an accessor); and a primitive's JOINTS_0 and WEIGHTS_0 made ready for the vertex stage.
// Failures throw LoadError naming the field.
#include "scene/animation.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace scene::gltf {

class Document;

std::vector<Rig::Skin> read_skins(Document& document, const std::vector<int>& node_of);

// Per vertex: each joint index checked against the skin's `joint_count`, the weights checked
// non-negative and scaled to sum to 1 (the exporters' rounding); a vertex whose weights are all zero
// follows its first joint alone.
void check_skin_attributes(const std::vector<glm::vec4>& joints, std::vector<glm::vec4>& weights, size_t joint_count,
                           const std::string& where, std::vector<glm::vec<4, uint16_t>>& joints_out);

}  // namespace scene::gltf
