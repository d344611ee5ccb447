#include "hal/image.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>

namespace hal {

bool load_image(const std::string& path, RgbImage& out, std::string* error) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    if (error) *error = path + ": cannot open image: " + OIIO::geterror();
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  const int channels = spec.nchannels;
  if (spec.width <= 0 || spec.height <= 0 || channels < 1) {
    if (error) *error = path + ": expected a non-empty image with at least one channel";
    return false;
  }
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
