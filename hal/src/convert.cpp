#include "hal/convert.h"

#include "base/image_codec.h"

#include <algorithm>
#include <string>

namespace hal {

namespace {

std::uint8_t clamp8(int v) {
  return static_cast<std::uint8_t>(std::clamp(v, 0, 255));
}

// BT.601 limited range in 8.8 fixed point: R = 1.164(Y-16) + 1.596(V-128), etc.
void yuv_to_rgb(int y, int u, int v, std::uint8_t* rgb) {
  const int c = 298 * (y - 16);
  const int d = u - 128;
  const int e = v - 128;
  rgb[0] = clamp8((c + 409 * e + 128) >> 8);
  rgb[1] = clamp8((c - 100 * d - 208 * e + 128) >> 8);
  rgb[2] = clamp8((c + 516 * d + 128) >> 8);
}

// The frame header of a JPEG: walks the marker segments up to the first SOFn (a SOF marker inside
// another segment's payload, such as Exif, is skipped with it) or the start of scan.
struct JpegFrame {
  int width = 0, height = 0, components = 0;
};
bool jpeg_frame(std::span<const std::uint8_t> jpeg, JpegFrame& frame, std::string& why) {
  if (jpeg.size() < 4 || jpeg[0] != 0xFF || jpeg[1] != 0xD8) {
    why = "no start-of-image marker";
    return false;
  }
  std::size_t i = 2;
  while (i + 1 < jpeg.size()) {
    if (jpeg[i] != 0xFF) {
      why = "expected a marker at byte " + std::to_string(i);
      return false;
    }
    const std::uint8_t marker = jpeg[i + 1];
    if (marker == 0xFF) {  // fill byte before a marker
      ++i;
      continue;
    }
    i += 2;
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) continue;  // no length
    if (marker == 0xD9 || marker == 0xDA) break;                         // end of image, start of scan: no frame header came
    if (i + 2 > jpeg.size()) break;
    const std::size_t length = static_cast<std::size_t>(jpeg[i] << 8 | jpeg[i + 1]);
    if (length < 2 || i + length > jpeg.size()) {
      why = "a segment runs past the end of the frame";
      return false;
    }
    const bool sof = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (sof) {
      if (length < 8) {
        why = "a frame header too short";
        return false;
      }
      frame.height = jpeg[i + 3] << 8 | jpeg[i + 4];
      frame.width = jpeg[i + 5] << 8 | jpeg[i + 6];
      frame.components = jpeg[i + 7];
      return true;
    }
    i += length;
  }
  why = "no frame header before the image data";
  return false;
}

}  // namespace

void yuyv_to_rgb(std::span<const std::uint8_t> src, int width, int height, int stride, RgbImage& out) {
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* row = src.data() + static_cast<std::size_t>(y) * stride;
    std::uint8_t* dst = out.at(0, y);
    // Each 4-byte group Y0 U Y1 V carries two pixels sharing one chroma pair.
    for (int x = 0; x + 1 < width; x += 2, row += 4, dst += 6) {
      yuv_to_rgb(row[0], row[1], row[3], dst);
      yuv_to_rgb(row[2], row[1], row[3], dst + 3);
    }
    // An odd width leaves a last pixel with only its Y and U inside the row (width * 2 bytes may be
    // all the stride there is): it takes its left neighbour's chroma, or none in a 1-pixel row.
    if (width % 2 == 1) {
      if (width > 1)
        yuv_to_rgb(row[0], row[-3], row[-1], dst);
      else
        yuv_to_rgb(row[0], 128, 128, dst);
    }
  }
}

// The decoder is made at the first frame, not with the camera: the image module is loaded then
// (the player loads it beside the frame loop once its first frame is shown), not at start-up.
struct MjpegDecoder::Impl {
  std::string missing;  // why there is no decoder
  std::unique_ptr<base::images::Reader> input;
};

MjpegDecoder::MjpegDecoder() : impl_(std::make_unique<Impl>()) {}
MjpegDecoder::~MjpegDecoder() = default;
MjpegDecoder::MjpegDecoder(MjpegDecoder&&) noexcept = default;
MjpegDecoder& MjpegDecoder::operator=(MjpegDecoder&&) noexcept = default;

bool MjpegDecoder::decode(std::span<const std::uint8_t> jpeg, RgbImage& out, std::string* error) {
  auto& in = impl_->input;
  if (!in && impl_->missing.empty()) in = base::images::make_reader("jpg", impl_->missing);
  if (!in) {
    if (error) *error = "JPEG decoder: " + impl_->missing;
    return false;
  }
  // The frame's size is checked before the decoder sees it: OpenImageIO's open() already starts
  // decompressing, and libjpeg allocates by the declared size, so a corrupt frame declaring
  // 65535x65535 asked for 4.4 GB (a fuzz finding) before the size could be refused.
  JpegFrame frame;
  std::string why;
  if (!jpeg_frame(jpeg, frame, why)) {
    if (error) *error = "MJPEG frame: not a decodable JPEG: " + why;
    return false;
  }
  if (frame.width != out.width || frame.height != out.height) {
    if (error)
      *error = "MJPEG frame: expected " + std::to_string(out.width) + "x" + std::to_string(out.height) + ", got " +
               std::to_string(frame.width) + "x" + std::to_string(frame.height);
    return false;
  }
  if (frame.components != 1 && frame.components != 3) {
    if (error) *error = "MJPEG frame: expected 1 or 3 colour components, got " + std::to_string(frame.components);
    return false;
  }
  // The decoder reads the frame where the driver mapped it, through an in-memory I/O proxy.
  base::images::Header spec;
  const bool opened = in->open("frame.jpg", jpeg.data(), jpeg.size(), spec, why);
  bool ok = opened;
  if (opened && (spec.width != out.width || spec.height != out.height)) {
    if (error)
      *error = "MJPEG frame: expected " + std::to_string(out.width) + "x" + std::to_string(out.height) + ", got " +
               std::to_string(spec.width) + "x" + std::to_string(spec.height);
    ok = false;
  } else if (opened) {
    // Grey JPEGs come through as one channel: read it, then replicate in place from the back.
    const int channels = std::min(spec.channels, 3);
    ok = in->read(channels, out.pixels.data(), 3, why);
    if (ok && channels == 1) {
      for (std::size_t i = static_cast<std::size_t>(out.width) * out.height; i-- > 0;) {
        const std::uint8_t v = out.pixels[i * 3];
        out.pixels[i * 3 + 1] = out.pixels[i * 3 + 2] = v;
      }
    }
    if (!ok && error) *error = "MJPEG frame: " + why;
  } else if (error) {
    *error = "MJPEG frame: not a decodable JPEG: " + why;
  }
  in->close();
  return ok;
}

}  // namespace hal
