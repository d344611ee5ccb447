#pragma once
// The parts of glTF's JSON schema the player relies on, checked on the parsed JSON before tinygltf
// reads it: tinygltf keeps a default for a property whose value has the wrong type or sign (a
// negative byteOffset silently becomes 0) and does not range-check indices it follows itself (an
// image's bufferView is read without a bounds check). Each returns the first problem as
// "field: what is wrong; expected ...", or empty.
#include <nlohmann/json_fwd.hpp>

#include <string>
#include <vector>

namespace scene::gltf {

// `warnings` receives what glTF-Validator reports as a warning and the loader can do without: a
// sampler value outside its list means the default for that field.
std::string schema_problem(const nlohmann::json& root, std::vector<std::string>& warnings);

// JSON has one kind of number; glTF-Validator accepts an integer written as 1.0 wherever an
// integer is expected, and so does the player: every float with an integral value (within 2^53)
// becomes an integer before the schema check and tinygltf, which both tell the two apart. Floats
// read as numbers are unaffected (both readers take an integer where a number is expected).
void integral_floats_to_integers(nlohmann::json& value);

}  // namespace scene::gltf
