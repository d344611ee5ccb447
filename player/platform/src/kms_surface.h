#pragma once
// EGL on GBM for the kms platform: the GBM device on the DRM fd, the EGL display, config and
// OpenGL ES context, and the scanout-capable window surface frames are drawn into. Also the
// buffers that surface hands out, which stay locked while they are on the screen or queued for it,
// and their DRM framebuffers.
#include "platform/platform.h"

#include <EGL/egl.h>
#include <gbm.h>

#include <cstdint>
#include <memory>
#include <string>

namespace platform::kms {

class Surface {
 public:
  // The display, a config whose native visual is a scanout format (XRGB8888, else ARGB8888) and
  // the context; no surface until resize(). Null and why otherwise.
  static std::unique_ptr<Surface> create(int fd, const std::string& device_path, bool debug_context, std::string& error);
  ~Surface();
  Surface(const Surface&) = delete;
  Surface& operator=(const Surface&) = delete;

  // A surface of `size` made current with the context, replacing the old one (whose buffers must
  // no longer be waited on: they are released here). False and why, the old one kept.
  bool resize(Size size, std::string& error);
  Size size() const { return size_; }
  const char* format_name() const { return format_ == GBM_FORMAT_XRGB8888 ? "XRGB8888" : "ARGB8888"; }
  const std::string& extension() const { return extension_; }

  // eglSwapBuffers, then the buffer it finished, locked: null and why in `error` otherwise.
  gbm_bo* swap(std::string& error);
  // The DRM framebuffer of a locked buffer, made once and kept with the buffer; 0 and why.
  std::uint32_t framebuffer_for(gbm_bo* bo, std::string& error);
  void release(gbm_bo* bo);

  // Where the locked buffers are: queued by a flip, on the screen after it or after a modeset.
  void flip_queued(gbm_bo* bo) { pending_ = bo; }
  void flip_completed();
  // The buffers of the old mode (and of a flip given up on) leave the screen with a modeset.
  void shown_by_modeset(gbm_bo* bo);
  bool showing() const { return shown_ != nullptr; }
  void release_all();

 private:
  Surface() = default;

  int fd_ = -1;
  std::string device_path_;
  bool modifiers_ = false;  // the driver takes framebuffers with format modifiers
  gbm_device* gbm_ = nullptr;
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLConfig config_ = nullptr;
  EGLContext context_ = EGL_NO_CONTEXT;
  std::string extension_;
  std::uint32_t format_ = GBM_FORMAT_XRGB8888;
  gbm_surface* surface_ = nullptr;
  EGLSurface egl_surface_ = EGL_NO_SURFACE;
  Size size_;
  gbm_bo* shown_ = nullptr;    // on the screen now
  gbm_bo* pending_ = nullptr;  // queued to flip at the next vblank (or a flip given up on)
};

}  // namespace platform::kms
