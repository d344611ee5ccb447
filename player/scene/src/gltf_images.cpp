#include "gltf_images.h"

#include "base/image_codec.h"
#include "gltf_document.h"

#include <png.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace scene::gltf {

// Nothing from the decoders reaches stderr: OpenImageIO's PNG reader lets libpng print "libpng
// error: ..." itself, so PNG goes through libpng's simplified API, which keeps every message in
// png_image::message; OpenImageIO's JPEG reader routes libjpeg's messages to its own error, which
// is read and dropped. Either way the one line is ours.
DecodedImage decode_image(const unsigned char* bytes, size_t size, const LoadOptions& options, std::string& problem) {
  auto skip = [&](const std::string& what) {
    problem = what;
    return DecodedImage{};
  };
  if (size < 4) return skip("image data is empty or truncated");
  // OpenImageIO picks the reader by file extension; glTF images are PNG or JPEG by magic number.
  const bool png = bytes[0] == 0x89 && bytes[1] == 'P', jpeg = bytes[0] == 0xFF && bytes[1] == 0xD8;
  if (!png && !jpeg) return skip("expected PNG or JPEG data");
  const std::string kind = png ? "PNG" : "JPEG";
  const std::string corrupt = "the " + kind + " data cannot be decoded (corrupt or truncated)";
  // From the header alone: the size is checked before a single pixel is decoded or allocated.
  auto size_problem = [&](uint64_t width, uint64_t height) -> std::string {
    const uint64_t limit = static_cast<uint64_t>(options.max_texture_size);
    const std::string dimensions = kind + " of " + std::to_string(width) + "x" + std::to_string(height);
    if (width == 0 || height == 0 || width > limit || height > limit)
      return dimensions + "; expected 1.." + std::to_string(limit) + " pixels per side";
    const uint64_t decoded = width * height * 4;
    if (decoded > options.image_budget_bytes)
      return dimensions + " needs " + std::to_string(decoded >> 20) + " MiB decoded; expected at most " +
             std::to_string(options.image_budget_bytes >> 20) +
             " MiB for this image (the per-image limit, or what is left of the scene's)";
    return {};
  };
  auto finish = [&](int width, int height, std::vector<unsigned char> pixels) {
    DecodedImage image;
    image.width = width;
    image.height = height;
    image.rgba = std::move(pixels);
    return image;
  };
  if (png) {
    png_image decoder{};
    decoder.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_memory(&decoder, bytes, size)) return skip(corrupt);
    if (const std::string too_large = size_problem(decoder.width, decoder.height); !too_large.empty()) {
      png_image_free(&decoder);
      return skip(too_large);
    }
    decoder.format = PNG_FORMAT_RGBA;  // grey, palette and 16-bit files all become 8-bit sRGB RGBA
    std::vector<unsigned char> pixels(PNG_IMAGE_SIZE(decoder));
    const int width = static_cast<int>(decoder.width), height = static_cast<int>(decoder.height);
    if (!png_image_finish_read(&decoder, nullptr, pixels.data(), 0, nullptr)) return skip(corrupt);
    return finish(width, height, std::move(pixels));
  }
  std::string why;
  const std::unique_ptr<base::images::Reader> input = base::images::make_reader("", why);
  if (!input) return skip(why);
  base::images::Header spec;
  if (!input->open("image.jpg", bytes, size, spec, why)) return skip(corrupt);
  if (spec.width <= 0 || spec.height <= 0) return skip(corrupt);
  if (const std::string too_large = size_problem(uint64_t(spec.width), uint64_t(spec.height)); !too_large.empty())
    return skip(too_large);
  std::vector<unsigned char> pixels(size_t(spec.width) * size_t(spec.height) * 4, 255);
  const int channels = std::min(spec.channels, 4);
  std::string messages;
  const bool read = input->read(channels, pixels.data(), 4, messages);
  // libjpeg decodes a truncated file to grey with only a warning: any message counts as a failure.
  if (!read || !messages.empty()) return skip(corrupt);
  if (channels < 3) {  // grey (+ alpha): spread grey over RGB
    for (size_t p = 0; p < pixels.size(); p += 4) {
      if (channels == 2) pixels[p + 3] = pixels[p + 1];
      pixels[p + 1] = pixels[p + 2] = pixels[p];
    }
  }
  return finish(spec.width, spec.height, std::move(pixels));
}

}  // namespace scene::gltf
