#include "gltf_bytes.h"
#include "base/read_file.h"

#include "scene/gltf_loader.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>

namespace scene::gltf {
namespace fs = std::filesystem;
namespace {

bool inside(const fs::path& root, const fs::path& candidate) {
  std::error_code ec;
  const fs::path resolved = fs::weakly_canonical(candidate, ec);
  if (ec) return false;
  auto [root_end, unused] = std::mismatch(root.begin(), root.end(), resolved.begin(), resolved.end());
  (void)unused;
  return root_end == root.end();
}

std::string hex32(uint32_t value) {
  char text[11];
  std::snprintf(text, sizeof text, "0x%08X", value);
  return text;
}

uint32_t u32_at(const std::string& bytes, size_t at) {
  uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, 4);
  return value;  // GLB is little-endian, like every board this player runs on
}

constexpr uint32_t kChunkJson = 0x4E4F534A, kChunkBin = 0x004E4942;

}  // namespace

// Reports files outside the folder as existing so that the read below refuses them by name,
// rather than tinygltf saying only "file not found".
bool confined_exists(const std::string& path, void*) {
  std::error_code ec;
  return fs::exists(path, ec);
}

std::string confined_expand(const std::string& path, void*) {
  return path;
}

bool confined_read(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  const auto* confinement = static_cast<Confinement*>(user);
  if (!inside(confinement->root, path)) {
    if (err) *err += "'" + path + "' lies outside the scene's folder " + confinement->root.string() + "; ";
    return false;
  }
  std::string bytes, error;
  if (!base::read_regular_file(path, "file the scene names", kMaxFileBytes, bytes, error)) {
    if (err) *err += error + "; ";
    return false;
  }
  out->assign(bytes.begin(), bytes.end());
  return true;
}

bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "the loader never writes files; ";
  return false;
}

// The GLB layout (glTF 2.0, 4.4): checked here because tinygltf reads chunk 1 at whatever offset
// chunk 0's length gives, and an empty file makes its reader index an empty vector.
std::string split_glb(const std::string& bytes, Glb& out, std::vector<std::string>& warnings) {
  if (bytes.size() < 12)
    return "the file is " + std::to_string(bytes.size()) + " bytes; expected a 12-byte GLB header and a JSON chunk";
  if (bytes.compare(0, 4, "glTF") != 0) return "bytes 0..3 are not the GLB magic 'glTF'";
  if (const uint32_t version = u32_at(bytes, 4); version != 2)
    return "GLB header version " + std::to_string(version) + "; expected 2";
  if (const uint32_t length = u32_at(bytes, 8); length != bytes.size())
    return "GLB header length " + std::to_string(length) + " differs from the file's " + std::to_string(bytes.size()) + " bytes";
  size_t at = 12;
  bool has_json = false;
  for (int chunk = 0; at < bytes.size(); ++chunk) {
    const std::string where = "GLB chunk " + std::to_string(chunk) + " at byte " + std::to_string(at);
    if (bytes.size() - at < 8) return where + ": its 8-byte header runs past the end of the file";
    const uint32_t length = u32_at(bytes, at), type = u32_at(bytes, at + 4);
    if (length > bytes.size() - at - 8)
      return where + ": length " + std::to_string(length) + " runs past the end of the file (" +
             std::to_string(bytes.size() - at - 8) + " bytes left)";
    if (length % 4 != 0) return where + ": length " + std::to_string(length) + " is not a multiple of 4";
    const std::string data = bytes.substr(at + 8, length);
    if (chunk == 0 && type != kChunkJson) return where + ": type " + hex32(type) + "; expected JSON (0x4E4F534A) first";
    if (chunk == 0) {
      out.json = data;
      has_json = true;
    } else if (type == kChunkJson) {
      return where + ": a second JSON chunk; expected one";
    } else if (type == kChunkBin) {
      if (chunk != 1) return where + ": a BIN chunk must directly follow the JSON chunk";
      out.bin = data;
      out.has_bin = true;
    } else {
      // The spec: "client implementations must ignore chunks with unknown types".
      warnings.push_back(where + ": unknown chunk type " + hex32(type) + "; ignored");
    }
    at += 8 + length;
  }
  if (!has_json) return "the GLB file has no JSON chunk";
  return {};
}

std::string join_glb(const Glb& glb) {
  std::string json = glb.json;
  while (json.size() % 4) json += ' ';
  std::string bytes = "glTF";
  auto put = [&](uint32_t value) { bytes.append(reinterpret_cast<const char*>(&value), 4); };
  const bool bin = glb.has_bin && !glb.bin.empty();
  put(2);
  put(static_cast<uint32_t>(12 + 8 + json.size() + (bin ? 8 + glb.bin.size() : 0)));
  put(static_cast<uint32_t>(json.size()));
  put(kChunkJson);
  bytes += json;
  if (bin) {
    put(static_cast<uint32_t>(glb.bin.size()));
    put(kChunkBin);
    bytes += glb.bin;
  }
  return bytes;
}

// Bracket depth outside strings, counted before any parser runs: tinygltf converts the parsed JSON
// to its own values by recursion, so 200,000 nested arrays would otherwise overflow the stack.
std::string nesting_problem(const std::string& text) {
  int depth = 0;
  bool in_string = false, escaped = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        return "JSON nests deeper than " + std::to_string(kMaxJsonDepth) + " levels at byte " + std::to_string(i) +
               "; expected at most " + std::to_string(kMaxJsonDepth);
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return {};
}

}  // namespace scene::gltf
