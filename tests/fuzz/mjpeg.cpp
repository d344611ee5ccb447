// MJPEG camera frames (hal::MjpegDecoder) as the V4L2 camera hands them over: whatever bytes the
// driver filled, into an image of the size the driver promised. To reach the decoding path and not
// only the size check, the first byte's low bit takes that size from the frame's own SOF marker;
// otherwise bytes 1..4 give it. Sizes are bounded to what a webcam sends.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

#include "hal/convert.h"

namespace {

// The size in the first SOF0..SOF2 segment, or false.
bool sof_size(std::span<const std::uint8_t> jpeg, int& width, int& height) {
  for (std::size_t i = 0; i + 8 < jpeg.size(); ++i) {
    if (jpeg[i] == 0xFF && jpeg[i + 1] >= 0xC0 && jpeg[i + 1] <= 0xC2) {
      height = jpeg[i + 5] << 8 | jpeg[i + 6];
      width = jpeg[i + 7] << 8 | jpeg[i + 8];
      return true;
    }
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 5) return 0;
  const std::span<const std::uint8_t> jpeg(data + 5, size - 5);
  int width = 1 + (data[1] | (data[2] & 0x07) << 8);
  int height = 1 + (data[3] | (data[4] & 0x07) << 8);
  if ((data[0] & 1) && !sof_size(jpeg, width, height)) return 0;
  if (width < 1 || height < 1 || width > 2048 || height > 2048) return 0;
  static hal::MjpegDecoder decoder;  // one per camera, reused for every frame, as the camera does
  hal::RgbImage out(width, height);
  std::string error;
  (void)decoder.decode(jpeg, out, &error);
  return 0;
}
