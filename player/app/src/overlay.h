#pragma once
// What the board would show, drawn into a corner of a desktop window: each status LED as a lamp
// with its name and pattern, and the player's state. Drawn on the CPU into a small image that is
// uploaded only when it changes, then blitted over the frame.
#include "gl/objects.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace app {

class Overlay {
 public:
  struct Lamp {
    std::string_view name, pattern;
    bool lit = false;
    bool operator==(const Lamp&) const = default;
  };
  // Redraws the panel if anything differs from the last call; cheap when nothing does. The names
  // must outlive the overlay (LED names from hal::Status, pattern names from hal::to_string).
  void update(std::string_view state, const std::vector<Lamp>& lamps, bool srgb_target);
  // Blits the panel into the top-left corner of `framebuffer` (of `height` pixels).
  void draw(unsigned framebuffer, int height) const;
  int width() const { return width_; }
  int panel_height() const { return height_; }

 private:
  void text(int x, int y, std::string_view s, const uint8_t colour[3]);
  void box(int x, int y, int w, int h, const uint8_t colour[3]);

  std::string_view state_;  // what the panel shows, to tell a change
  std::vector<Lamp> lamps_;
  int width_ = 0, height_ = 0;
  std::vector<uint8_t> pixels_;  // RGBA, row 0 at the bottom (GL order)
  gl::Texture texture_;
  gl::Framebuffer fbo_;
  int texture_width_ = 0, texture_height_ = 0;
  bool texture_srgb_ = false;
};

}  // namespace app
