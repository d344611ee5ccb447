#pragma once
// glTF animations to scene::Animation: the channels that move nodes of the shown scene (`node_of`
// maps a file node to the rig's, -1 where the shown scene does not hold it). Samplers are checked
// as the validator checks them (inputs increasing, outputs as many as the interpolation needs,
// the formats glTF allows; a weights channel's node must show a mesh with morph targets). Failures
// throw LoadError naming the field.
#include "scene/animation.h"

#include <string>
#include <vector>

namespace scene::gltf {

class Document;

std::vector<Animation> read_animations(Document& document, const std::vector<int>& node_of, const Rig& rig);

}  // namespace scene::gltf
