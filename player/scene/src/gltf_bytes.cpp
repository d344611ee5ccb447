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

namespace {

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// "%XX" sequences to bytes; false on a malformed one.
bool percent_decode(const std::string& text, std::string& out) {
  out.clear();
  out.reserve(text.size());
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '%') {
      out += text[i];
      continue;
    }
    if (i + 2 >= text.size() || hex_digit(text[i + 1]) < 0 || hex_digit(text[i + 2]) < 0) return false;
    out += static_cast<char>(hex_digit(text[i + 1]) * 16 + hex_digit(text[i + 2]));
    i += 2;
  }
  return true;
}

int base64_digit(char c) {
  if (c >= 'A' && c <= 'Z') return c - 'A';
  if (c >= 'a' && c <= 'z') return c - 'a' + 26;
  if (c >= '0' && c <= '9') return c - '0' + 52;
  if (c == '+' || c == '-') return 62;  // '-' and '_': the URL-safe alphabet some writers use
  if (c == '/' || c == '_') return 63;
  return -1;
}

}  // namespace

bool read_confined(const fs::path& folder, const std::string& uri, std::vector<unsigned char>& out, std::string& problem) {
  std::string relative;
  if (!percent_decode(uri, relative)) {
    problem = "'" + uri + "' has a malformed %-escape; expected %XX with two hex digits";
    return false;
  }
  const fs::path path = folder / relative;
  if (!inside(folder, path)) {
    problem = "'" + uri + "' lies outside the scene's folder " + folder.string();
    return false;
  }
  std::string bytes;
  if (!base::read_regular_file(path.string(), "file the scene names", kMaxFileBytes, bytes, problem)) return false;
  out.assign(bytes.begin(), bytes.end());
  return true;
}

bool decode_data_uri(const std::string& uri, std::vector<unsigned char>& out, std::string& problem) {
  const size_t comma = uri.find(',');
  if (uri.rfind("data:", 0) != 0 || comma == std::string::npos) {
    problem = "a data: URI without its ','; expected data:[<type>][;base64],<data>";
    return false;
  }
  const std::string header = uri.substr(5, comma - 5), payload = uri.substr(comma + 1);
  const bool base64 = header.size() >= 7 && header.compare(header.size() - 7, 7, ";base64") == 0;
  out.clear();
  if (!base64) {
    std::string text;
    if (!percent_decode(payload, text)) {
      problem = "the data: URI has a malformed %-escape; expected %XX with two hex digits";
      return false;
    }
    out.assign(text.begin(), text.end());
    return true;
  }
  out.reserve(payload.size() / 4 * 3);
  uint32_t bits = 0;
  int pending = 0;
  size_t padding = 0;
  for (size_t i = 0; i < payload.size(); ++i) {
    const char c = payload[i];
    if (c == '=') {
      ++padding;
      continue;
    }
    const int digit = base64_digit(c);
    if (digit < 0 || padding > 0) {
      problem = "the data: URI's base64 has '" + std::string(1, c) + "' at character " + std::to_string(i) +
                "; expected A-Z, a-z, 0-9, +, / and = only at the end";
      return false;
    }
    bits = (bits << 6) | static_cast<uint32_t>(digit);
    if (++pending == 4) {
      out.push_back(static_cast<unsigned char>(bits >> 16));
      out.push_back(static_cast<unsigned char>(bits >> 8));
      out.push_back(static_cast<unsigned char>(bits));
      bits = 0;
      pending = 0;
    }
  }
  if (pending == 1 || padding > 2) {
    problem = "the data: URI's base64 ends mid-byte; expected a length that decodes to whole bytes";
    return false;
  }
  if (pending == 2) out.push_back(static_cast<unsigned char>(bits >> 4));
  if (pending == 3) {
    out.push_back(static_cast<unsigned char>(bits >> 10));
    out.push_back(static_cast<unsigned char>(bits >> 2));
  }
  return true;
}

std::string uri_problem(const std::string& uri) {
  if (uri.empty()) return "empty; expected a file inside the scene's folder";
  if (uri.find("://") != std::string::npos) return "'" + uri + "' is a URL; expected a file inside the scene's folder";
  const fs::path path(uri);
  if (path.is_absolute() || uri.front() == '/' || uri.front() == '\\')
    return "'" + uri + "' is an absolute path; expected a path relative to the scene's folder";
  int depth = 0;
  for (const fs::path& part : path) {
    if (part == "..")
      --depth;
    else if (part != "." && !part.empty())
      ++depth;
    if (depth < 0) return "'" + uri + "' escapes the scene's folder";
  }
  return {};
}

// The GLB layout (glTF 2.0, 4.4): checked here because tinygltf reads chunk 1 at whatever offset
// chunk 0's length gives, and an empty file makes its reader index an empty vector.
std::string split_glb(const std::string& bytes, Glb& out, std::vector<std::string>& warnings) {
  if (bytes.size() < 12)
    return "the file is " + std::to_string(bytes.size()) + " bytes; expected a 12-byte GLB header and a JSON chunk";
  if (bytes.compare(0, 4, "glTF") != 0) return "bytes 0..3 are not the GLB magic 'glTF'";
  if (const uint32_t version = u32_at(bytes, 4); version != 2)
    return "GLB header version " + std::to_string(version) + "; expected 2";
  const uint32_t declared = u32_at(bytes, 8);
  if (declared > bytes.size())
    return "GLB header length " + std::to_string(declared) + " exceeds the file's " + std::to_string(bytes.size()) +
           " bytes (the file is truncated)";
  if (declared < 12) return "GLB header length " + std::to_string(declared) + "; expected at least the 12-byte header";
  // glTF-Validator warns about bytes after the declared length (GLB_EXTRA_DATA); they are not glTF.
  if (declared < bytes.size())
    warnings.push_back("GLB: " + std::to_string(bytes.size() - declared) + " bytes after the declared length " +
                       std::to_string(declared) + "; ignored");
  const size_t end = declared;
  size_t at = 12;
  bool has_json = false;
  for (int chunk = 0; at < end; ++chunk) {
    const std::string where = "GLB chunk " + std::to_string(chunk) + " at byte " + std::to_string(at);
    if (end - at < 8) return where + ": its 8-byte header runs past the end of the file";
    const uint32_t length = u32_at(bytes, at), type = u32_at(bytes, at + 4);
    if (length > end - at - 8)
      return where + ": length " + std::to_string(length) + " runs past the end of the file (" + std::to_string(end - at - 8) +
             " bytes left)";
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
