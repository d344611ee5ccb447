#include "hal/image.h"

#include "base/image_codec.h"
#include "base/read_file.h"

#include <algorithm>

namespace hal {

bool load_image(const std::string& path, RgbImage& out, std::string* error) {
  // Read by the one function that refuses FIFOs and devices, then decoded from memory: OIIO would
  // open the path itself and wait on a FIFO.
  std::string bytes, why;
  if (!base::read_regular_file(path, "image", kMaxImageFileBytes, bytes, why)) {
    if (error) *error = why;
    return false;
  }
  const std::unique_ptr<base::images::Reader> in = base::images::make_reader("", why);
  if (!in) {
    if (error) *error = path + ": cannot open image: " + why;
    return false;
  }
  base::images::Header spec;
  if (!in->open(path, bytes.data(), bytes.size(), spec, why)) {
    if (error) *error = path + ": cannot open image: " + why;
    return false;
  }
  if (spec.width <= 0 || spec.height <= 0 || spec.channels < 1) {
    if (error) *error = path + ": expected a non-empty image with at least one channel";
    return false;
  }
  // The header's size is checked before any pixel is allocated: a PNG can claim 60000x60000.
  if (spec.width > kMaxImageSide || spec.height > kMaxImageSide ||
      static_cast<std::uint64_t>(spec.width) * static_cast<std::uint64_t>(spec.height) > kMaxImagePixels) {
    if (error)
      *error = path + ": the image is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + "; at most " +
               std::to_string(kMaxImageSide) + " pixels per side and " + std::to_string(kMaxImagePixels / 1000000) +
               " million pixels are read";
    return false;
  }
  const int channels = std::min(spec.channels, 3);  // grey, RGB; alpha and beyond are not looked at
  std::vector<std::uint8_t> raw(static_cast<std::size_t>(spec.width) * spec.height * channels);
  if (!in->read(channels, raw.data(), 0, why)) {
    if (error) *error = path + ": cannot read pixels: " + why;
    return false;
  }
  out.resize(spec.width, spec.height);
  const std::size_t n = static_cast<std::size_t>(spec.width) * spec.height;
  for (std::size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) out.pixels[i * 3 + c] = raw[i * channels + std::min(c, channels < 3 ? 0 : c)];
  }
  return true;
}

bool save_image(const std::string& path, const RgbImage& image, std::string* error) {
  base::images::WriteSpec spec;
  spec.width = image.width;
  spec.height = image.height;
  spec.channels = 3;
  std::string why;
  switch (base::images::write(path, spec, image.pixels.data(), why)) {
    case base::images::WriteFailure::none:
      return true;
    case base::images::WriteFailure::no_writer:
      if (error) *error = path + ": no image writer for this file extension: " + why;
      return false;
    default:
      if (error) *error = path + ": cannot write image: " + why;
      return false;
  }
}

}  // namespace hal
