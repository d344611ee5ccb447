#pragma once
// Camera pixel formats to RGB. YUYV is converted here (BT.601 limited range, what UVC cameras send);
// MJPEG goes through OpenImageIO, whose libjpeg-turbo also decodes frames that omit the Huffman
// tables (many webcams do).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "hal/image.h"

namespace hal {

// `stride` is bytes per source row (V4L2's bytesperline), at least width * 2; `src` holds at least
// stride * height bytes. `out` must already be width x height.
void yuyv_to_rgb(std::span<const std::uint8_t> src, int width, int height, int stride, RgbImage& out);

class MjpegDecoder {
 public:
  MjpegDecoder();
  ~MjpegDecoder();
  MjpegDecoder(MjpegDecoder&&) noexcept;
  MjpegDecoder& operator=(MjpegDecoder&&) noexcept;
  // Decodes into `out`, which must already be the expected size; a frame of another size is an error.
  // The decoder library allocates internally; this wrapper does not.
  bool decode(std::span<const std::uint8_t> jpeg, RgbImage& out, std::string* error);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hal
