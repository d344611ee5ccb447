// YUYV camera frames (hal::yuyv_to_rgb) with the checks the V4L2 camera makes before converting:
// the driver's width, height and bytesperline (raised to width * 2 when smaller), and a frame of
// at least stride * height bytes. The first 5 bytes choose the format within a webcam's range.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "hal/convert.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 5) return 0;
  const int width = 1 + (data[0] | (data[1] & 0x03) << 8);  // 1..1024
  const int height = 1 + data[2] % 64;
  const int bytesperline = data[3] | data[4] << 8;
  const int stride = std::max(bytesperline, width * 2);  // camera_v4l2.cpp's min_stride
  const std::span<const std::uint8_t> frame(data + 5, size - 5);
  if (frame.size() < static_cast<std::size_t>(stride) * height) return 0;  // refused before conversion
  hal::RgbImage out(width, height);
  hal::yuyv_to_rgb(frame, width, height, stride, out);
  return 0;
}
