#pragma once
// What `player render --dump DIR` writes, read back: the surface points the SSAO pass saw and the
// camera and AO settings it used. The benchmark can also fill a View in memory and skip the files.
#include "aoref/image.h"

#include <glm/glm.hpp>

#include <string>
#include <vector>

namespace aoref {

// The inputs of a reference: one image's surface points, the eye and the AO radii.
struct View {
  glm::dvec3 eye{0.0};        // world-space camera position
  std::vector<double> radii;  // world units, largest first (the player's order)
  Image position;             // 4 channels: world-space position, A = 1 on objects, 0 on background
  Image normal;               // 4 channels: world-space unit normal, A as above

  int width() const { return position.width; }
  int height() const { return position.height; }
  bool is_object(size_t pixel) const { return position.at(pixel, 3) > 0.5f; }
};

struct Dump {
  std::string dir;
  std::string scene;  // the scene spec the player rendered ("builtin:NAME" or a path)
  View view;
  glm::dmat4 view_matrix{1.0}, projection{1.0};
  double near = 0.0, far = 0.0;
  int samples = 0;             // SSAO samples per radius
  double bias_fraction = 0.0;  // SSAO depth bias as a fraction of each radius
  std::string pattern, blur;
  Image depth;               // 1 channel: linear view depth, 0 on background
  Image ao_raw, ao_blurred;  // 1 channel each
};

// Reads DIR/camera.json and the five EXRs, checking every field and image size it uses. Returns
// false with the file, the field and what was expected in `error`.
bool read_dump(const std::string& dir, Dump& out, std::string& error);

}  // namespace aoref
