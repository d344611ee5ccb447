#include "image_io.h"

#include <OpenImageIO/imageio.h>
#include <unistd.h>

#include <filesystem>

namespace app {
namespace {

// OpenImageIO says only "Could not open file"; the usual causes are the folder's, so name them.
std::string why_not_writable(const std::string& path, const std::string& fallback) {
  std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (folder.empty()) folder = ".";
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec)) return "the folder " + folder.string() + " does not exist";
  if (::access(folder.c_str(), W_OK) != 0) return "the folder " + folder.string() + " is not writable";
  return fallback;
}

}  // namespace

bool write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba, std::string& error) {
  auto output = OIIO::ImageOutput::create(path);
  if (!output) {
    error = path + ": cannot create an image writer (" + OIIO::geterror() + ")";
    return false;
  }
  OIIO::ImageSpec spec(width, height, 4, OIIO::TypeDesc::UINT8);
  if (!output->open(path, spec)) {
    error = path + ": cannot write: " + why_not_writable(path, output->geterror());
    return false;
  }
  if (!output->write_image(OIIO::TypeDesc::UINT8, rgba.data()) || !output->close()) {
    error = path + ": cannot write (" + output->geterror() + ")";
    return false;
  }
  return true;
}

bool write_exr(const std::string& path, int width, int height, int channels, const std::vector<float>& values,
               const std::vector<std::string>& channel_names, std::string& error) {
  auto output = OIIO::ImageOutput::create(path);
  if (!output) {
    error = path + ": cannot create an EXR writer (" + OIIO::geterror() + ")";
    return false;
  }
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::FLOAT);
  spec.channelnames = channel_names;
  spec.attribute("compression", "zip");
  const OIIO::stride_t row = static_cast<OIIO::stride_t>(width) * channels * static_cast<OIIO::stride_t>(sizeof(float));
  // Start at the last row in memory (the top of the picture) and walk down with a negative stride.
  const float* top = values.data() + static_cast<size_t>(height - 1) * static_cast<size_t>(width) * static_cast<size_t>(channels);
  if (!output->open(path, spec)) {
    error = path + ": cannot write: " + why_not_writable(path, output->geterror());
    return false;
  }
  if (!output->write_image(OIIO::TypeDesc::FLOAT, top, OIIO::AutoStride, -row) || !output->close()) {
    error = path + ": cannot write (" + output->geterror() + ")";
    return false;
  }
  return true;
}

}  // namespace app
