#include "scene/gltf_loader.h"
#include "base/read_file.h"

#include "gltf_accessors.h"
#include "gltf_builder.h"
#include "gltf_bytes.h"
#include "gltf_images.h"
#include "gltf_schema.h"

#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <iterator>
#include <system_error>

// The loader's pieces live in scene::gltf, one job a file: gltf_bytes (the container and confined
// file access), gltf_schema (the JSON checks tinygltf skips), gltf_images (decoding), gltf_accessors
// (bounds-checked reads), gltf_builder (the Scene). This file runs them in order.
namespace scene {
namespace fs = std::filesystem;
using gltf::Confinement;
using gltf::Glb;
using gltf::ImageContext;
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
  if (const std::string problem = gltf::schema_problem(root, report.warnings); !problem.empty()) return refuse(problem);
  if (const std::string problem = gltf::uri_problem(root); !problem.empty()) return refuse(problem);
  root = json();  // tinygltf parses its own copy; this one need not stay in memory beside it

  Confinement confinement{fs::weakly_canonical(fs::absolute(file)).parent_path()};
  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks({gltf::confined_exists, gltf::confined_expand, gltf::confined_read, gltf::refuse_write, &confinement});
  ImageContext images;
  images.options = &options;
  loader.SetImageLoader(gltf::load_image, &images);
  tinygltf::Model model;
  std::string error, warning;
  const std::string base_dir = fs::absolute(file).parent_path().string();
  bool parsed = false;
  if (binary) {
    const std::string joined = gltf::join_glb(glb);
    parsed = loader.LoadBinaryFromMemory(&model, &error, &warning, reinterpret_cast<const unsigned char*>(joined.data()),
                                         static_cast<unsigned int>(joined.size()), base_dir);
  } else {
    parsed = loader.LoadASCIIFromString(&model, &error, &warning, glb.json.data(), static_cast<unsigned int>(glb.json.size()),
                                        base_dir);
  }
  if (!parsed) {
    while (!error.empty() && (error.back() == '\n' || error.back() == ' ' || error.back() == ';')) error.pop_back();
    return refuse("not a valid glTF 2.0 file: " + (error.empty() ? "unknown parse error" : error));
  }
  // Images tinygltf could not read (a missing external file) reach no decoder; they too are white.
  for (size_t i = 0; i < model.images.size(); ++i) {
    const int index = static_cast<int>(i);
    if (model.images[i].image.empty() && !images.problems.count(index))
      images.problems[index] = "'" + model.images[i].uri + "' cannot be read";
  }
  for (const auto& [index, problem] : images.problems)
    report.warnings.push_back("images[" + std::to_string(index) + "]: " + problem + "; its texture is drawn white");
  try {
    out = gltf::build_scene(model, report, fs::path(file).filename().string());
  } catch (const gltf::LoadError& e) {
    return refuse(e.message);
  }
  return true;
}

}  // namespace scene
