#pragma once
// What the glTF loader's tests share: a fixture with a scratch folder, a one-triangle document
// whose buffer is a data: URI, and helpers to write, load and refuse files.
#include "scene/gltf_loader.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace {
namespace fs = std::filesystem;
using nlohmann::json;

const fs::path kShared = PLAYER_SHARED_DIR;

inline std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t chunk = static_cast<uint32_t>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) chunk |= static_cast<uint32_t>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) chunk |= bytes[i + 2];
    out += table[(chunk >> 18) & 63];
    out += table[(chunk >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(chunk >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[chunk & 63] : '=';
  }
  return out;
}

template <typename T>
void append(std::vector<unsigned char>& bytes, std::initializer_list<T> values) {
  for (T value : values) {
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    bytes.insert(bytes.end(), raw, raw + sizeof(T));
  }
}

class GltfLoader : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("gltf_loader_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_ / "scene");
  }
  void TearDown() override { fs::remove_all(dir_); }

  // One triangle (or the given positions and indices) in a single buffer, as a data URI.
  json triangle(std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0}, std::vector<uint16_t> indices = {0, 1, 2}) {
    std::vector<unsigned char> bytes;
    for (float p : positions) append<float>(bytes, {p});
    const size_t index_offset = bytes.size();
    for (uint16_t i : indices) append<uint16_t>(bytes, {i});
    while (bytes.size() % 4) bytes.push_back(0);
    return json{{"asset", {{"version", "2.0"}}},
                {"scene", 0},
                {"scenes", {{{"nodes", {0}}}}},
                {"nodes", {{{"mesh", 0}}}},
                {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
                {"buffers", {{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}}}},
                {"bufferViews",
                 {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", index_offset}},
                  {{"buffer", 0}, {"byteOffset", index_offset}, {"byteLength", indices.size() * 2}}}},
                {"accessors",
                 {{{"bufferView", 0}, {"componentType", 5126}, {"count", positions.size() / 3}, {"type", "VEC3"}},
                  {{"bufferView", 1}, {"componentType", 5123}, {"count", indices.size()}, {"type", "SCALAR"}}}}};
  }

  fs::path write(const json& doc, const std::string& name = "scene/model.gltf") {
    const fs::path path = dir_ / name;
    std::ofstream(path) << doc.dump();
    return path;
  }

  // Loads and expects failure; returns the error after checking it names the file.
  std::string error_of(const fs::path& path) {
    scene::Scene out;
    out.name = "untouched";
    scene::LoadReport report;
    EXPECT_FALSE(scene::load_gltf(path, out, report));
    EXPECT_EQ(out.name, "untouched");
    EXPECT_NE(report.error.find(path.string()), std::string::npos) << report.error;
    return report.error;
  }

  scene::Scene load_ok(const fs::path& path) {
    scene::Scene out;
    scene::LoadReport report;
    EXPECT_TRUE(scene::load_gltf(path, out, report)) << report.error;
    return out;
  }

  fs::path dir_;
};

}  // namespace
