#pragma once
// Images: PNG through libpng, JPEG through OpenImageIO (base/image_codec.h), sizes checked
// from the header before anything is decoded. An image that cannot be used (not PNG or JPEG,
// corrupt, truncated, too large) does not stop the scene: its texture is drawn white and the report
// says why, so a kiosk still shows the geometry.
#include "scene/gltf_loader.h"

#include <cstddef>
#include <string>

namespace scene::gltf {

struct DecodedImage;

// The image's pixels as 8-bit RGBA, or an empty image with the reason in `problem`.
DecodedImage decode_image(const unsigned char* bytes, size_t size, const LoadOptions& options, std::string& problem);

}  // namespace scene::gltf
