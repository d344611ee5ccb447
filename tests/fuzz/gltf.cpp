// The glTF loader (scene::load) from bytes, built twice: as a .glb (PLAYER_FUZZ_GLTF_EXT ".glb")
// and as a .gltf, since the extension picks the parser. Each input becomes the one scene file of a
// fake scene folder that also holds the files its external URIs may name (seeds and gltf.dict use
// these names), so buffer and image loading, decoding and the folder-escape checks run too. Returning
// an error is fine; a throw, an abort or a sanitizer report is a finding.
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

#include "fuzz_dir.h"
#include "scene/load.h"

#ifndef PLAYER_FUZZ_GLTF_EXT
#error "PLAYER_FUZZ_GLTF_EXT: expected \".glb\" or \".gltf\" from tests/fuzz/CMakeLists.txt"
#endif

namespace {

// A 2x2 RGB PNG: red, green / blue, white.
constexpr unsigned char kPng[] = {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
                                  0x52, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x02, 0x08, 0x02, 0x00, 0x00, 0x00, 0xfd,
                                  0xd4, 0x9a, 0x73, 0x00, 0x00, 0x00, 0x12, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0xf8,
                                  0xcf, 0xc0, 0xc0, 0x00, 0xc2, 0x0c, 0xff, 0x81, 0x00, 0x00, 0x1f, 0xee, 0x05, 0xfb, 0x0b,
                                  0xd9, 0x68, 0x8b, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
// A JPEG cut off after its SOI and the start of an APP0 segment.
constexpr unsigned char kTruncatedJpeg[] = {0xff, 0xd8, 0xff, 0xe0, 0x00, 0x10, 0x4a, 0x46};

// One triangle: three float VEC3 positions (36 bytes), then uint16 indices 0 1 2 and 2 bytes of pad.
std::string triangle_bin() {
  const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const std::uint16_t indices[4] = {0, 1, 2, 0};
  std::string bytes(reinterpret_cast<const char*>(positions), sizeof positions);
  bytes.append(reinterpret_cast<const char*>(indices), sizeof indices);
  return bytes;
}

void write(const std::filesystem::path& path, const void* data, std::size_t size) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(static_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out) std::abort();  // the fake folder is the fixture: without it, nothing here is tested
}

const std::filesystem::path& scene_folder() {
  static const std::filesystem::path dir = [] {
    const std::filesystem::path d = fuzz::scratch_dir() / "scene";
    std::filesystem::create_directories(d / "textures");
    const std::string bin = triangle_bin();
    write(d / "buffer.bin", bin.data(), bin.size());
    write(d / "texture.png", kPng, sizeof kPng);
    write(d / "textures" / "texture.png", kPng, sizeof kPng);
    write(d / "broken.jpg", kTruncatedJpeg, sizeof kTruncatedJpeg);
    write(d / "empty.bin", "", 0);
    // Outside the scene's folder: a URI reaching it must be refused, not read.
    write(fuzz::scratch_dir() / "outside.bin", bin.data(), bin.size());
    return d;
  }();
  return dir;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = (scene_folder() / ("scene" PLAYER_FUZZ_GLTF_EXT)).string();
  write(path, data, size);
  scene::Scene scene;
  std::string error;
  std::ostringstream log;
  (void)scene::load(path, scene, error, log);
  return 0;
}
