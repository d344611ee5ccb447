#pragma once
// Images for tinygltf's image callback: PNG through libpng, JPEG through OpenImageIO, sizes checked
// from the header before anything is decoded. An image that cannot be used (not PNG or JPEG,
// corrupt, truncated, too large) does not stop the scene: its texture is drawn white and the report
// says why, so a kiosk still shows the geometry.
#include "scene/gltf_loader.h"

#include <map>
#include <string>

namespace tinygltf {
struct Image;
}

namespace scene::gltf {

struct ImageContext {
  const LoadOptions* options = nullptr;
  std::map<int, std::string> problems;  // image index -> why it is drawn white
};

// tinygltf's LoadImageDataFunction; `user` is an ImageContext. Always returns true (tinygltf would
// drop the whole scene on false); a refused image is left empty with its reason in `problems`.
bool load_image(tinygltf::Image* image, int index, std::string* err, std::string* warn, int req_width, int req_height,
                const unsigned char* bytes, int size, void* user);

}  // namespace scene::gltf
