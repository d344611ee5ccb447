#pragma once
// Scene assembly from a parsed glTF model: the shown scene's node tree walked into instances, its
// triangle primitives converted to meshes once each, materials and textures. Throws LoadError
// (gltf_accessors.h) on the first problem, naming the field.
#include "scene/gltf_loader.h"

namespace tinygltf {
class Model;
}

namespace scene::gltf {

Scene build_scene(const tinygltf::Model& model, LoadReport& report, const std::string& name);

}  // namespace scene::gltf
