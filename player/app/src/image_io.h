#pragma once
// Image files through OpenImageIO (base/image_codec.h): PNG for what people look at, float EXR for what tools evaluate.
#include <cstdint>
#include <string>
#include <vector>

namespace app {

// rgba: width x height x 4 bytes, row 0 at the top. Returns false and says why.
bool write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba, std::string& error);
// values: width x height x channels floats, row 0 at the BOTTOM (GL order); written top row first.
bool write_exr(const std::string& path, int width, int height, int channels, const std::vector<float>& values,
               const std::vector<std::string>& channel_names, std::string& error);

}  // namespace app
