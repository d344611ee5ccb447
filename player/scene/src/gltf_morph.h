#pragma once
// glTF morph targets (3.7.2.2): a primitive's position and normal displacements, the weights a
// node shows its mesh at, and, once the animations are read, which meshes keep their targets for
// the frames to reshape. Failures throw LoadError naming the field.
#include "scene/animation.h"
#include "scene/scene.h"

#include <tiny_gltf.h>

#include <string>
#include <vector>

namespace scene::gltf {

class Document;

// The POSITION and NORMAL displacements of each of `primitive`'s targets, as many as its
// vertices; a target that moves no positions (or no normals) gets an empty list.
Mesh::Morph read_morph_targets(Document& document, const tinygltf::Primitive& primitive, size_t vertex_count,
                               const std::string& where, bool quantized);

// The weights node `node_index` shows its mesh at: the node's own, else the mesh's, else zeros;
// refused where a list's length is not the mesh's target count.
std::vector<float> default_weights(const tinygltf::Model& model, int node_index, size_t target_count);

// The number of morph targets of a glTF mesh (every primitive has as many; refused otherwise).
size_t target_count(const tinygltf::Mesh& mesh, const std::string& where);

// After the animations are read: a mesh whose node no weights channel moves drops its targets
// (its shape is final); one that keeps them gets a box that holds every shape the keyed weights
// (and its rest weights) can make, each weight taken over its range independently.
void settle_morphs(Scene& scene, const Rig& rig);

}  // namespace scene::gltf
