#pragma once
// Float images as the dump writes them: interleaved channels, row 0 at the TOP (EXR order).
#include <cstddef>
#include <string>
#include <vector>

namespace aoref {

struct Image {
  int width = 0, height = 0, channels = 0;
  std::vector<float> values;  // width x height x channels, row 0 at the top

  Image() = default;
  Image(int w, int h, int c, float fill = 0.0f);
  size_t pixel_count() const { return static_cast<size_t>(width) * static_cast<size_t>(height); }
  float& at(size_t pixel, int channel = 0) {
    return values[pixel * static_cast<size_t>(channels) + static_cast<size_t>(channel)];
  }
  float at(size_t pixel, int channel = 0) const {
    return values[pixel * static_cast<size_t>(channels) + static_cast<size_t>(channel)];
  }
  bool same_size(const Image& other) const { return width == other.width && height == other.height; }
};

// Reads any image OpenImageIO can open as float. Returns false and says why, naming the file.
bool read_image(const std::string& path, Image& out, std::string& error);
// Writes a float EXR (zip compression) with the given channel names, one per channel.
bool write_exr(const std::string& path, const Image& image, const std::vector<std::string>& channel_names, std::string& error);

// Writes 8-bit RGB pixels (row 0 at the top) in the format the name's extension says (e.g. PNG).
bool write_rgb8(const std::string& path, int width, int height, const std::vector<unsigned char>& rgb, std::string& error);

// Where and by how much an estimate is off: each object pixel (depth > 0) shows estimate -
// reference, red where the estimate is darker (too much AO), blue where it is lighter, full at
// +-full_scale, white at 0; background black.
std::vector<unsigned char> error_map(const Image& estimate, const Image& reference, const Image& depth, float full_scale);

}  // namespace aoref
