#include "overlay.h"

#include "blit_source.h"

#include <algorithm>
#include <cctype>
#include <utility>

namespace app {
namespace {

struct Glyph {
  char c;
  uint8_t rows[7];  // top row first; bit 4 is the leftmost column
};
// A 5x7 font for the few characters the panel writes (upper case; lower case is drawn as upper).
constexpr Glyph kFont[] = {
    {'-', {0x00, 0x00, 0x00, 0x1f, 0x00, 0x00, 0x00}}, {'.', {0x00, 0x00, 0x00, 0x00, 0x00, 0x0c, 0x0c}},
    {'0', {0x0e, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0e}}, {'1', {0x04, 0x0c, 0x04, 0x04, 0x04, 0x04, 0x0e}},
    {'2', {0x0e, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1f}}, {'3', {0x1e, 0x01, 0x01, 0x0e, 0x01, 0x01, 0x1e}},
    {'4', {0x02, 0x06, 0x0a, 0x12, 0x1f, 0x02, 0x02}}, {'5', {0x1f, 0x10, 0x1e, 0x01, 0x01, 0x11, 0x0e}},
    {'6', {0x0e, 0x10, 0x10, 0x1e, 0x11, 0x11, 0x0e}}, {'7', {0x1f, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
    {'8', {0x0e, 0x11, 0x11, 0x0e, 0x11, 0x11, 0x0e}}, {'9', {0x0e, 0x11, 0x11, 0x0f, 0x01, 0x01, 0x0e}},
    {':', {0x00, 0x04, 0x04, 0x00, 0x04, 0x04, 0x00}}, {'A', {0x0e, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11}},
    {'B', {0x1e, 0x11, 0x11, 0x1e, 0x11, 0x11, 0x1e}}, {'C', {0x0f, 0x10, 0x10, 0x10, 0x10, 0x10, 0x0f}},
    {'D', {0x1e, 0x11, 0x11, 0x11, 0x11, 0x11, 0x1e}}, {'E', {0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x1f}},
    {'F', {0x1f, 0x10, 0x10, 0x1e, 0x10, 0x10, 0x10}}, {'G', {0x0f, 0x10, 0x10, 0x13, 0x11, 0x11, 0x0f}},
    {'H', {0x11, 0x11, 0x11, 0x1f, 0x11, 0x11, 0x11}}, {'I', {0x0e, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0e}},
    {'J', {0x07, 0x02, 0x02, 0x02, 0x02, 0x12, 0x0c}}, {'K', {0x11, 0x12, 0x14, 0x18, 0x14, 0x12, 0x11}},
    {'L', {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1f}}, {'M', {0x11, 0x1b, 0x15, 0x15, 0x11, 0x11, 0x11}},
    {'N', {0x11, 0x19, 0x15, 0x13, 0x11, 0x11, 0x11}}, {'O', {0x0e, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e}},
    {'P', {0x1e, 0x11, 0x11, 0x1e, 0x10, 0x10, 0x10}}, {'Q', {0x0e, 0x11, 0x11, 0x11, 0x15, 0x12, 0x0d}},
    {'R', {0x1e, 0x11, 0x11, 0x1e, 0x14, 0x12, 0x11}}, {'S', {0x0f, 0x10, 0x10, 0x0e, 0x01, 0x01, 0x1e}},
    {'T', {0x1f, 0x04, 0x04, 0x04, 0x04, 0x04, 0x04}}, {'U', {0x11, 0x11, 0x11, 0x11, 0x11, 0x11, 0x0e}},
    {'V', {0x11, 0x11, 0x11, 0x11, 0x11, 0x0a, 0x04}}, {'W', {0x11, 0x11, 0x11, 0x15, 0x15, 0x1b, 0x11}},
    {'X', {0x11, 0x11, 0x0a, 0x04, 0x0a, 0x11, 0x11}}, {'Y', {0x11, 0x11, 0x0a, 0x04, 0x04, 0x04, 0x04}},
    {'Z', {0x1f, 0x01, 0x02, 0x04, 0x08, 0x10, 0x1f}},
};

constexpr int kScale = 2;  // font pixels per glyph pixel
constexpr int kAdvance = 6 * kScale;
constexpr int kLine = 10 * kScale;
constexpr int kMargin = 6;
constexpr uint8_t kBackground[3] = {20, 22, 28};
constexpr uint8_t kText[3] = {230, 230, 230};
constexpr uint8_t kLampOff[3] = {60, 60, 60};
constexpr uint8_t kLampOn[3] = {90, 230, 90};

const Glyph* glyph(char c) {
  const char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (const Glyph& g : kFont)
    if (g.c == upper) return &g;
  return nullptr;  // a space, or a character the font lacks: left blank
}

}  // namespace

void Overlay::box(int x, int y, int w, int h, const uint8_t colour[3]) {
  for (int row = std::max(0, y); row < std::min(height_, y + h); ++row)
    for (int column = std::max(0, x); column < std::min(width_, x + w); ++column) {
      // y counts from the top; pixels_ is stored bottom-up for GL.
      uint8_t* p =
          &pixels_[(static_cast<size_t>(height_ - 1 - row) * static_cast<size_t>(width_) + static_cast<size_t>(column)) * 4];
      std::copy_n(colour, 3, p);
      p[3] = 255;
    }
}

void Overlay::text(int x, int y, std::string_view s, const uint8_t colour[3]) {
  for (char c : s) {
    if (const Glyph* g = glyph(c))
      for (int row = 0; row < 7; ++row)
        for (int column = 0; column < 5; ++column)
          if (g->rows[row] & (0x10 >> column)) box(x + column * kScale, y + row * kScale, kScale, kScale, colour);
    x += kAdvance;
  }
}

void Overlay::update(std::string_view state, const std::vector<Lamp>& lamps, bool srgb_target) {
  // Compared field by field, so a frame where nothing changed costs no allocation.
  if (fbo_ && state == state_ && srgb_target == texture_srgb_ && lamps == lamps_) return;
  state_ = state;
  lamps_ = lamps;
  size_t longest = state.size() + 7;  // "state: "
  for (const Lamp& lamp : lamps) longest = std::max(longest, lamp.name.size() + lamp.pattern.size() + 2);
  width_ = 2 * kMargin + kLine + static_cast<int>(longest) * kAdvance;
  height_ = 2 * kMargin + static_cast<int>(1 + lamps.size()) * kLine;
  pixels_.assign(static_cast<size_t>(width_) * static_cast<size_t>(height_) * 4, 0);
  box(0, 0, width_, height_, kBackground);
  text(kMargin, kMargin, "state: " + std::string(state), kText);
  int y = kMargin + kLine;
  for (const Lamp& lamp : lamps) {
    box(kMargin, y, 7 * kScale, 7 * kScale, lamp.lit ? kLampOn : kLampOff);
    text(kMargin + kLine, y, std::string(lamp.name) + " " + std::string(lamp.pattern), kText);
    y += kLine;
  }
  if (width_ != texture_width_ || height_ != texture_height_ || srgb_target != texture_srgb_) {
    // The panel's bytes are meant as written: the texture takes the target's encoding.
    BlitSource source = make_blit_source(width_, height_, srgb_target);
    texture_ = std::move(source.texture);
    fbo_ = std::move(source.framebuffer);
    texture_srgb_ = srgb_target;
    texture_width_ = width_;
    texture_height_ = height_;
  }
  gl::api.BindTexture(GL_TEXTURE_2D, texture_.id());
  gl::api.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl::api.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, pixels_.data());
  gl::api.BindTexture(GL_TEXTURE_2D, 0);
}

void Overlay::draw(unsigned framebuffer, int height) const {
  if (!fbo_) return;
  gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_.id());
  gl::api.BindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer);
  const int top = height - kMargin;
  gl::api.BlitFramebuffer(0, 0, width_, height_, kMargin, top - height_, kMargin + width_, top, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace app
