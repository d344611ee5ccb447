#pragma once
// Scene assembly from a parsed glTF document: the shown scene's node tree walked into instances, its
// triangle primitives converted to meshes once each, materials, textures and lights. Throws LoadError
// (gltf_accessors.h) on the first problem, naming the field.
#include "scene/gltf_loader.h"

namespace scene::gltf {

class Document;

class LightReader;
// `lights`: the file's light definitions, which the shown scene's nodes place.
Scene build_scene(Document& document, const LightReader& lights, LoadReport& report, const std::string& name);

}  // namespace scene::gltf
