#include "screenshot.h"

#include "base/image_codec.h"
#include "base/read_file.h"
#include "base/unique_fd.h"

#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <vector>

namespace fleet {
namespace {

// A 2x2 box filter: each output pixel the mean of four.
std::vector<std::uint8_t> halved(const std::vector<std::uint8_t>& rgb, int& width, int& height) {
  const int w = width / 2, h = height / 2;
  std::vector<std::uint8_t> out(static_cast<std::size_t>(w) * h * 3);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) {
        const auto at = [&](int sx, int sy) { return rgb[(static_cast<std::size_t>(sy) * width + sx) * 3 + c]; };
        const int sum = at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1);
        out[(static_cast<std::size_t>(y) * w + x) * 3 + c] = static_cast<std::uint8_t>((sum + 2) / 4);
      }
  width = w;
  height = h;
  return out;
}

}  // namespace

bool jpeg_within(const std::string& png_path, std::size_t max_bytes, std::string& jpeg, int& width, int& height,
                 std::string& error) {
  std::string png;
  if (!base::read_regular_file(png_path, "screenshot", 256 * base::kMiB, png, error)) return false;
  std::unique_ptr<base::images::Reader> reader = base::images::make_reader("", error);
  if (!reader) return false;
  base::images::Header header;
  if (!reader->open(png_path, png.data(), png.size(), header, error)) return false;
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(header.width) * header.height * 3);
  std::string messages;
  const bool read = reader->read(3, rgb.data(), 0, messages);
  reader->close();
  if (!read) {
    error = png_path + ": " + messages;
    return false;
  }
  width = header.width;
  height = header.height;
  // The encoder writes files only: one in the temporary folder, read back and removed.
  std::string scratch = (std::filesystem::temp_directory_path() / "ssao-player-fleet-XXXXXX.jpg").string();
  const base::UniqueFd fd(mkstemps(scratch.data(), 4));
  if (!fd) {
    error = "cannot make a temporary file like " + scratch;
    return false;
  }
  for (;;) {
    base::images::WriteSpec spec;
    spec.width = width;
    spec.height = height;
    spec.channels = 3;
    spec.compression = "jpeg:85";
    if (base::images::write(scratch, spec, rgb.data(), error) != base::images::WriteFailure::none) break;
    if (!base::read_regular_file(scratch, "JPEG", 256 * base::kMiB, jpeg, error)) break;
    if (jpeg.size() <= max_bytes) {
      unlink(scratch.c_str());
      return true;
    }
    if (width < 32 || height < 32) {
      error = "a " + std::to_string(width) + "x" + std::to_string(height) + " JPEG still takes " +
              base::byte_size_text(jpeg.size()) + ", over the " + base::byte_size_text(max_bytes) + " allowed";
      break;
    }
    rgb = halved(rgb, width, height);
  }
  unlink(scratch.c_str());
  return false;
}

}  // namespace fleet
