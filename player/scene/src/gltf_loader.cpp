#include "scene/gltf_loader.h"
#include "base/read_file.h"

#include "gltf_accessors.h"
#include "gltf_builder.h"
#include "gltf_bytes.h"
#include "gltf_document.h"
#include "gltf_lights.h"
#include "gltf_schema.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iterator>
#include <optional>
#include <system_error>

// The loader's pieces live in scene::gltf, one job a file: gltf_bytes (the container, data: URIs and
// confined file access), gltf_schema (the JSON checks tinygltf skips), gltf_document (tinygltf's
// structure and the bytes behind it, read when used), gltf_images and gltf_meshopt (decoding),
// gltf_accessors (bounds-checked reads), gltf_builder (the Scene). This file runs them in order.
namespace scene {
namespace fs = std::filesystem;
using gltf::Document;
using gltf::Glb;
using nlohmann::json;

bool load_gltf(const fs::path& file, Scene& out, LoadReport& report, const LoadOptions& options) {
  report = LoadReport{};
  const std::string name = file.string();
  auto refuse = [&](const std::string& problem) {
    report.error = name + ": " + problem;
    report.warnings.clear();
    return false;
  };
  std::error_code ec;
  if (!fs::exists(file, ec)) return refuse("no such file");
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (extension != ".gltf" && extension != ".glb") return refuse("expected a .gltf or .glb file");
  const bool binary = extension == ".glb";

  std::string bytes, why;
  if (!base::read_regular_file(name, "scene", gltf::kMaxFileBytes, bytes, why)) {
    report.error = why;
    report.warnings.clear();
    return false;
  }
  if (bytes.empty())
    return refuse("not a valid glTF 2.0 file: the file is empty (0 bytes); expected glTF 2.0 " +
                  std::string(binary ? "binary" : "JSON"));
  Glb glb;
  if (binary) {
    // Layout and nesting problems keep the "not a valid glTF" of a parse error: the file is not
    // glTF at all, rather than glTF with one field wrong.
    if (const std::string problem = gltf::split_glb(bytes, glb, report.warnings); !problem.empty())
      return refuse("not a valid glTF 2.0 file: " + problem);
  } else {
    glb.json = std::move(bytes);
  }
  // The spec forbids a byte-order mark but lets readers ignore one, as most do (and tinygltf
  // would refuse it): ignored, with a warning so the exporter can be fixed.
  if (glb.json.compare(0, 3, "\xEF\xBB\xBF") == 0) {
    glb.json.erase(0, 3);
    report.warnings.push_back("the JSON starts with a UTF-8 byte-order mark, which glTF forbids; ignored");
  }
  if (const std::string problem = gltf::nesting_problem(glb.json); !problem.empty())
    return refuse("not a valid glTF 2.0 file: " + problem);
  json root;
  try {
    root = json::parse(glb.json);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number like 1e400
    std::string what = e.what();
    if (const size_t at = what.find("] "); at != std::string::npos) what.erase(0, at + 2);  // "[json.exception...] "
    return refuse("not a valid glTF 2.0 file: " + what);
  }
  glb.json = std::string();  // parsed: only the BIN chunk is needed from here on
  gltf::integral_floats_to_integers(root);
  if (const std::string problem = gltf::schema_problem(root, report.warnings); !problem.empty()) return refuse(problem);
  // Before tinygltf, whose own light checks would refuse without naming the field.
  std::optional<gltf::LightReader> lights;
  try {
    lights.emplace(root, report.warnings);
  } catch (const gltf::LoadError& e) {
    return refuse(e.message);
  }

  Document document(std::move(root), std::move(glb), fs::weakly_canonical(fs::absolute(file)).parent_path(), options,
                    report.warnings);
  if (const std::string error = document.parse(); !error.empty()) {
    std::string text = error;
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ' || text.back() == ';')) text.pop_back();
    return refuse("not a valid glTF 2.0 file: " + text);
  }
  try {
    out = gltf::build_scene(document, *lights, report, fs::path(file).filename().string());
  } catch (const gltf::LoadError& e) {
    return refuse(e.message);
  } catch (const std::bad_alloc&) {
    return refuse("the scene needs more memory than there is; nothing of it is shown");
  } catch (const std::exception& e) {
    // Every expected problem is a LoadError naming its field; this is the backstop that keeps an
    // overlooked one (a JSON value of an unexpected type, a library's own exception) from
    // stopping the player.
    return refuse(std::string("cannot be read: ") + e.what());
  }
  return true;
}

}  // namespace scene
