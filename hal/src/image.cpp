#include "hal/image.h"

#include "base/read_file.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

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
  OIIO::Filesystem::IOMemReader memory(bytes.data(), bytes.size());
  auto in = OIIO::ImageInput::open(path, nullptr, &memory);
  if (!in) {
    if (error) *error = path + ": cannot open image: " + OIIO::geterror();
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels < 1) {
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
  const int channels = std::min(spec.nchannels, 3);  // grey, RGB; alpha and beyond are not looked at
  std::vector<std::uint8_t> raw(static_cast<std::size_t>(spec.width) * spec.height * channels);
  if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, raw.data())) {
    if (error) *error = path + ": cannot read pixels: " + in->geterror();
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
  auto out = OIIO::ImageOutput::create(path);
  if (!out) {
    if (error) *error = path + ": no image writer for this file extension: " + OIIO::geterror();
    return false;
  }
  OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
  if (!out->open(path, spec) || !out->write_image(OIIO::TypeDesc::UINT8, image.pixels.data()) || !out->close()) {
    if (error) *error = path + ": cannot write image: " + out->geterror();
    return false;
  }
  return true;
}

}  // namespace hal
