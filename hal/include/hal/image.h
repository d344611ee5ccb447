#pragma once
// The one image type hal exchanges with the player: tightly packed 8-bit RGB, row-major, top row first.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace hal {

struct RgbImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 3

  RgbImage() = default;
  RgbImage(int w, int h) : width(w), height(h), pixels(static_cast<std::size_t>(w) * h * 3, 0) {}
  bool empty() const { return width <= 0 || height <= 0; }
  std::uint8_t* at(int x, int y) { return &pixels[(static_cast<std::size_t>(y) * width + x) * 3]; }
  const std::uint8_t* at(int x, int y) const { return &pixels[(static_cast<std::size_t>(y) * width + x) * 3]; }
  // Reuses the buffer when the size is unchanged, so a capture loop allocates once.
  void resize(int w, int h) {
    width = w;
    height = h;
    pixels.resize(static_cast<std::size_t>(w) * h * 3);
  }
};

// What load_image reads: a regular file of at most this many bytes, whose header says at most this
// size. A camera frame is far smaller; a header that claims more is refused before pixels are allocated.
inline constexpr std::size_t kMaxImageFileBytes = 256u << 20;
inline constexpr int kMaxImageSide = 16384;
inline constexpr std::uint64_t kMaxImagePixels = 64'000'000;

// OpenImageIO load/save. Any channel count is accepted on load (grey is replicated, alpha dropped).
// A FIFO, a device or an oversized file or image is refused (base/read_file.h). On failure they
// return false and put "<path>: <reason>" into *error.
bool load_image(const std::string& path, RgbImage& out, std::string* error);
bool save_image(const std::string& path, const RgbImage& image, std::string* error);

}  // namespace hal
