#pragma once
// A display mounted turned: the frame is drawn at the logical orientation into a target of its own
// and turned onto the surface by quarter turns at the end (rotate.frag). Many boards' display
// controllers have no scanout rotation, so the renderer does it; at 0 degrees nothing is allocated
// and frames go straight to the surface.
#include "gl/objects.h"
#include "render/passes.h"
#include "render/programs.h"

#include <string>

namespace render {

// 0, 90, 180 or 270 (clockwise, as the image is seen); false and why otherwise.
bool valid_rotation(int degrees, std::string& error);

class Rotation {
 public:
  // For a surface of surface_width x surface_height whose framebuffer encodes sRGB or not. Returns
  // false and says why (a GL object that could not be made).
  bool configure(Programs& programs, int degrees, int surface_width, int surface_height, bool surface_srgb, std::string& error);
  int degrees() const { return degrees_; }
  // The size frames are drawn at: the surface's, its sides swapped for 90 and 270.
  int width() const { return width_; }
  int height() const { return height_; }
  // Where frames are drawn: the surface itself at 0 degrees, else the logical target.
  PresentTarget target(const PresentTarget& surface) const;
  // Turns the logical frame onto the surface; nothing at 0 degrees.
  void finish(const Programs& programs, const PresentTarget& surface) const;

 private:
  int degrees_ = 0, width_ = 0, height_ = 0, surface_width_ = 0, surface_height_ = 0;
  bool srgb_ = false;
  gl::Texture texture_;
  gl::Framebuffer framebuffer_;
};

}  // namespace render
