#include "aoref/image.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

namespace aoref {

Image::Image(int w, int h, int c, float fill)
    : width(w), height(h), channels(c), values(static_cast<size_t>(w) * static_cast<size_t>(h) * static_cast<size_t>(c), fill) {}

bool read_image(const std::string& path, Image& out, std::string& error) {
  auto input = OIIO::ImageInput::open(path);
  if (!input) {
    error = path + ": cannot open (" + OIIO::geterror() + ")";
    return false;
  }
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    error = path + ": expected a non-empty image, found " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
            " with " + std::to_string(spec.nchannels) + " channels";
    return false;
  }
  Image image(spec.width, spec.height, spec.nchannels);
  if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.values.data())) {
    error = path + ": cannot read the pixels (" + input->geterror() + ")";
    return false;
  }
  out = std::move(image);
  return true;
}

bool write_exr(const std::string& path, const Image& image, const std::vector<std::string>& channel_names, std::string& error) {
  if (static_cast<int>(channel_names.size()) != image.channels) {
    error = path + ": " + std::to_string(channel_names.size()) + " channel names for an image of " +
            std::to_string(image.channels) + " channels";
    return false;
  }
  auto output = OIIO::ImageOutput::create(path);
  if (!output) {
    error = path + ": cannot create an EXR writer (" + OIIO::geterror() + ")";
    return false;
  }
  OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
  spec.channelnames = channel_names;
  spec.attribute("compression", "zip");
  if (!output->open(path, spec) || !output->write_image(OIIO::TypeDesc::FLOAT, image.values.data()) || !output->close()) {
    error = path + ": cannot write (" + output->geterror() + ")";
    return false;
  }
  return true;
}

bool write_rgb8(const std::string& path, int width, int height, const std::vector<unsigned char>& rgb, std::string& error) {
  auto output = OIIO::ImageOutput::create(path);
  if (!output) {
    error = path + ": cannot create a writer for this file type (" + OIIO::geterror() + ")";
    return false;
  }
  const OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  if (!output->open(path, spec) || !output->write_image(OIIO::TypeDesc::UINT8, rgb.data()) || !output->close()) {
    error = path + ": cannot write (" + output->geterror() + ")";
    return false;
  }
  return true;
}

std::vector<unsigned char> error_map(const Image& estimate, const Image& reference, const Image& depth, float full_scale) {
  std::vector<unsigned char> rgb(depth.pixel_count() * 3, 0);
  for (size_t i = 0; i < depth.pixel_count(); ++i) {
    if (depth.at(i) <= 0.0f) continue;
    const float e = std::clamp((estimate.at(i) - reference.at(i)) / full_scale, -1.0f, 1.0f);
    const auto fade = static_cast<unsigned char>(std::lround(255.0f * (1.0f - std::abs(e))));
    rgb[i * 3 + 0] = e < 0.0f ? fade : 255;
    rgb[i * 3 + 1] = fade;
    rgb[i * 3 + 2] = e > 0.0f ? fade : 255;
  }
  return rgb;
}

}  // namespace aoref
