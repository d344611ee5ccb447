#include "image_io.h"

#include "base/image_codec.h"

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

namespace {

bool write_image(const std::string& path, const base::images::WriteSpec& spec, const void* pixels, const char* writer,
                 std::string& error) {
  std::string why;
  switch (base::images::write(path, spec, pixels, why)) {
    case base::images::WriteFailure::none:
      return true;
    case base::images::WriteFailure::no_writer:
      error = path + ": cannot create " + writer + " (" + why + ")";
      return false;
    case base::images::WriteFailure::open:
      error = path + ": cannot write: " + why_not_writable(path, why);
      return false;
    case base::images::WriteFailure::write:
      error = path + ": cannot write (" + why + ")";
      return false;
  }
  return false;
}

}  // namespace

bool write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba, std::string& error) {
  base::images::WriteSpec spec;
  spec.width = width;
  spec.height = height;
  spec.channels = 4;
  return write_image(path, spec, rgba.data(), "an image writer", error);
}

bool write_exr(const std::string& path, int width, int height, int channels, const std::vector<float>& values,
               const std::vector<std::string>& channel_names, std::string& error) {
  base::images::WriteSpec spec;
  spec.width = width;
  spec.height = height;
  spec.channels = channels;
  spec.floating = true;
  spec.channel_names = channel_names;
  spec.compression = "zip";
  // Start at the last row in memory (the top of the picture) and walk down with a negative stride.
  spec.row_stride = -static_cast<std::ptrdiff_t>(width) * channels * static_cast<std::ptrdiff_t>(sizeof(float));
  const float* top = values.data() + static_cast<size_t>(height - 1) * static_cast<size_t>(width) * static_cast<size_t>(channels);
  return write_image(path, spec, top, "an EXR writer", error);
}

}  // namespace app
