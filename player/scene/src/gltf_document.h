#pragma once
// A parsed glTF file with the bytes behind it: tinygltf maps the JSON to structures, and this owns
// everything it would otherwise read itself (buffers, images, compressed buffer views). Bytes are
// fetched when the scene first needs them, so a buffer nothing reads (an unused buffer without a
// uri, a URL, a meshopt fallback) is never opened, and an image no material shows is never decoded.
// Failures throw LoadError (gltf_accessors.h) naming the field that led there.
#include "gltf_bytes.h"
#include "scene/gltf_loader.h"

#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace scene::gltf {

struct Bytes {
  const unsigned char* data = nullptr;
  size_t size = 0;
};

struct DecodedImage {
  int width = 0, height = 0;
  std::vector<unsigned char> rgba;  // empty: the image cannot be used and is drawn white (warned once)
};

class Document {
 public:
  // `root` is the checked, normalised JSON (the schema check has run); `glb` the file's chunks
  // (json only for .gltf); `folder` the canonical folder external files must stay inside.
  Document(nlohmann::json root, Glb glb, std::filesystem::path folder, const LoadOptions& options,
           std::vector<std::string>& warnings);

  // Parses the structure with tinygltf; returns its error, or empty.
  std::string parse();

  const tinygltf::Model& model() const { return model_; }
  const nlohmann::json& root() const { return root_; }
  bool uses_extension(const std::string& name) const;

  // The bytes of buffer view `index` (decompressed when it carries EXT_meshopt_compression), all
  // of them within their buffer. `field` names the reference, for the error.
  Bytes view_bytes(int index, const std::string& field);
  // Image `index` decoded to 8-bit RGBA, or empty with a warning given once.
  const DecodedImage& image(int index, const std::string& field);
  // Counts `bytes` the loader is about to decode against LoadOptions::decoded_budget_bytes, and
  // refuses (LoadError naming `field`) before anything is allocated when the total would exceed it.
  void charge(size_t bytes, const std::string& field);

 private:
  const std::vector<unsigned char>& buffer(int index, const std::string& field);
  std::vector<unsigned char> read_uri(const std::string& uri, const std::string& field, size_t expected_bytes);

  nlohmann::json root_;
  Glb glb_;
  std::filesystem::path folder_;
  const LoadOptions& options_;
  std::vector<std::string>& warnings_;
  tinygltf::Model model_;
  std::map<int, std::vector<unsigned char>> buffers_;
  std::map<int, std::vector<unsigned char>> decoded_views_;
  std::map<int, DecodedImage> images_;
  size_t decoded_bytes_ = 0;
};

}  // namespace scene::gltf
