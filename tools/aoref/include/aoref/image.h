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
  float& at(size_t pixel, int channel = 0) { return values[pixel * static_cast<size_t>(channels) + static_cast<size_t>(channel)]; }
  float at(size_t pixel, int channel = 0) const { return values[pixel * static_cast<size_t>(channels) + static_cast<size_t>(channel)]; }
  bool same_size(const Image& other) const { return width == other.width && height == other.height; }
};

// Reads any image OpenImageIO can open as float. Returns false and says why, naming the file.
bool read_image(const std::string& path, Image& out, std::string& error);
// Writes a float EXR (zip compression) with the given channel names, one per channel.
bool write_exr(const std::string& path, const Image& image, const std::vector<std::string>& channel_names,
               std::string& error);

}  // namespace aoref
