#pragma once
// A picture the CPU drew, kept on the GPU to be blitted over frames (the LED panel, a self-check
// frame): a texture in the encoding of the framebuffer it is blitted to, attached to a framebuffer
// to read from. A blit decodes an sRGB source and encodes into an sRGB target, so with the target's
// encoding the bytes arrive as written.
#include "gl/gl_api.h"
#include "gl/objects.h"

namespace app {

struct BlitSource {
  gl::Texture texture;
  gl::Framebuffer framebuffer;
};

inline BlitSource make_blit_source(int width, int height, bool srgb_target) {
  BlitSource source{gl::make_texture(), gl::make_framebuffer()};
  gl::api.BindTexture(GL_TEXTURE_2D, source.texture.id());
  gl::api.TexStorage2D(GL_TEXTURE_2D, 1, srgb_target ? GL_SRGB8_ALPHA8 : GL_RGBA8, width, height);
  gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, source.framebuffer.id());
  gl::api.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, source.texture.id(), 0);
  gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  return source;
}

}  // namespace app
