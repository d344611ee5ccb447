// libpng and libjpeg directly, not the player's image module (base/image_codec.h): the agent stays
// a small resident process (16 MB) where OpenImageIO's module and its libraries would make it 130.
#include "screenshot.h"

#include "base/read_file.h"

#include <jpeglib.h>
#include <png.h>

#include <csetjmp>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
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

struct JpegErrors {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

// libjpeg's default on an error is exit(): back to encode() instead, with its words.
[[noreturn]] void jpeg_failed(j_common_ptr info) {
  auto* errors = reinterpret_cast<JpegErrors*>(info->err);
  errors->manager.format_message(info, errors->message);
  std::longjmp(errors->jump, 1);
}

bool encode(const std::vector<std::uint8_t>& rgb, int width, int height, std::string& jpeg, std::string& error) {
  jpeg_compress_struct info{};
  JpegErrors errors{};
  info.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = jpeg_failed;
  unsigned char* bytes = nullptr;
  unsigned long size = 0;
  if (setjmp(errors.jump) != 0) {
    jpeg_destroy_compress(&info);
    std::free(bytes);
    error = std::string("JPEG: ") + errors.message;
    return false;
  }
  jpeg_create_compress(&info);
  jpeg_mem_dest(&info, &bytes, &size);
  info.image_width = static_cast<JDIMENSION>(width);
  info.image_height = static_cast<JDIMENSION>(height);
  info.input_components = 3;
  info.in_color_space = JCS_RGB;
  jpeg_set_defaults(&info);
  jpeg_set_quality(&info, 85, TRUE);
  jpeg_start_compress(&info, TRUE);
  while (info.next_scanline < info.image_height) {
    auto* row = const_cast<JSAMPLE*>(&rgb[static_cast<std::size_t>(info.next_scanline) * static_cast<std::size_t>(width) * 3]);
    jpeg_write_scanlines(&info, &row, 1);
  }
  jpeg_finish_compress(&info);
  jpeg.assign(reinterpret_cast<const char*>(bytes), size);
  jpeg_destroy_compress(&info);
  std::free(bytes);
  return true;
}

}  // namespace

bool jpeg_within(const std::string& png_path, std::size_t max_bytes, std::string& jpeg, int& width, int& height,
                 std::string& error) {
  std::string png;
  if (!base::read_regular_file(png_path, "screenshot", 256 * base::kMiB, png, error)) return false;
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (png_image_begin_read_from_memory(&image, png.data(), png.size()) == 0) {
    error = png_path + ": not a PNG (" + image.message + ")";
    return false;
  }
  image.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> rgb(PNG_IMAGE_SIZE(image));
  if (png_image_finish_read(&image, nullptr, rgb.data(), 0, nullptr) == 0) {
    error = png_path + ": " + image.message;
    png_image_free(&image);
    return false;
  }
  width = static_cast<int>(image.width);
  height = static_cast<int>(image.height);
  for (;;) {
    if (!encode(rgb, width, height, jpeg, error)) return false;
    if (jpeg.size() <= max_bytes) return true;
    if (width < 32 || height < 32) {
      error = "a " + std::to_string(width) + "x" + std::to_string(height) + " JPEG still takes " +
              base::byte_size_text(jpeg.size()) + ", over the " + base::byte_size_text(max_bytes) + " allowed";
      return false;
    }
    rgb = halved(rgb, width, height);
  }
}

}  // namespace fleet
