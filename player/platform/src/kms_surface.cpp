#include "kms_surface.h"

#include "egl_util.h"

#include "base/errno_text.h"

#include <EGL/eglext.h>
#include <drm_fourcc.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <vector>

namespace platform::kms {
namespace {

// A buffer's framebuffer, removed when GBM destroys the buffer.
struct FbData {
  int fd;
  std::uint32_t fb;
};

void destroy_fb(gbm_bo* bo, void* data) {
  (void)bo;
  auto* fb = static_cast<FbData*>(data);
  if (fb->fb != 0) drmModeRmFB(fb->fd, fb->fb);
  delete fb;
}

// A window config whose native visual is the scanout format: XRGB8888, else ARGB8888.
bool choose_config(EGLDisplay display, EGLConfig& config, std::uint32_t& format) {
  const EGLint wanted[] = {EGL_RENDERABLE_TYPE,
                           EGL_OPENGL_ES3_BIT_KHR,
                           EGL_SURFACE_TYPE,
                           EGL_WINDOW_BIT,
                           EGL_RED_SIZE,
                           8,
                           EGL_GREEN_SIZE,
                           8,
                           EGL_BLUE_SIZE,
                           8,
                           EGL_NONE};
  EGLint count = 0;
  eglChooseConfig(display, wanted, nullptr, 0, &count);
  std::vector<EGLConfig> configs(static_cast<size_t>(std::max(count, 0)));
  if (count > 0) eglChooseConfig(display, wanted, configs.data(), count, &count);
  for (std::uint32_t scanout : {GBM_FORMAT_XRGB8888, GBM_FORMAT_ARGB8888})
    for (EGLConfig candidate : configs) {
      EGLint visual = 0;
      if (eglGetConfigAttrib(display, candidate, EGL_NATIVE_VISUAL_ID, &visual) &&
          static_cast<std::uint32_t>(visual) == scanout) {
        config = candidate;
        format = scanout;
        return true;
      }
    }
  return false;
}

}  // namespace

std::unique_ptr<Surface> Surface::create(int fd, const std::string& device_path, bool debug_context, std::string& error) {
  auto surface = std::unique_ptr<Surface>(new Surface());
  Surface& self = *surface;
  self.fd_ = fd;
  self.device_path_ = device_path;
  std::uint64_t cap = 0;
  // Framebuffers get a modifier only where the driver takes them and the buffer has a real one:
  // vkms refuses DRM_FORMAT_MOD_INVALID, which is what Mesa's software buffers report.
  self.modifiers_ = drmGetCap(fd, DRM_CAP_ADDFB2_MODIFIERS, &cap) == 0 && cap != 0;
  self.gbm_ = gbm_create_device(fd);
  if (self.gbm_ == nullptr) {
    error = "kms: gbm_create_device on " + device_path + " failed (" + base::errno_text(errno) + ")";
    return nullptr;
  }
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  self.extension_ = egl::has_extension(client, "EGL_KHR_platform_gbm") ? "EGL_KHR_platform_gbm" : "EGL_MESA_platform_gbm";
  if (get_platform_display == nullptr || !egl::has_extension(client, self.extension_.c_str())) {
    error = "kms: the EGL library offers no GBM platform (EGL_KHR_platform_gbm or EGL_MESA_platform_gbm)";
    return nullptr;
  }
  self.display_ = get_platform_display(EGL_PLATFORM_GBM_KHR, self.gbm_, nullptr);
  EGLint major = 0, minor = 0;
  std::string why;
  if (self.display_ == EGL_NO_DISPLAY || !egl::initialize(self.display_, major, minor, why)) {
    error = "kms: no EGL display on GBM for " + device_path + (why.empty() ? "" : " (" + why + ")");
    return nullptr;
  }
  if (!choose_config(self.display_, self.config_, self.format_)) {
    error = "kms: no EGL config renders OpenGL ES 3 into an XRGB8888 or ARGB8888 GBM surface";
    return nullptr;
  }
  self.context_ = egl::create_context(self.display_, self.config_, major, minor, debug_context, why);
  if (self.context_ == EGL_NO_CONTEXT) {
    error = "kms: " + why;
    return nullptr;
  }
  return surface;
}

Surface::~Surface() {
  // The locked buffers go back first: Mesa frees a surface's buffers, locked or not, with its EGL
  // surface, and gbm_surface_release_buffer would then read freed memory.
  release_all();
  if (display_ != EGL_NO_DISPLAY) {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (egl_surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, egl_surface_);
    if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
  }
  if (surface_ != nullptr) gbm_surface_destroy(surface_);
  // The display is terminated before GBM goes: EGL's GBM platform holds the device.
  if (display_ != EGL_NO_DISPLAY) eglTerminate(display_);
  if (gbm_ != nullptr) gbm_device_destroy(gbm_);
}

bool Surface::resize(Size size, std::string& error) {
  gbm_surface* surface = gbm_surface_create(gbm_, static_cast<std::uint32_t>(size.width), static_cast<std::uint32_t>(size.height),
                                            format_, GBM_BO_USE_SCANOUT | GBM_BO_USE_RENDERING);
  if (surface == nullptr) {
    error = "kms: gbm_surface_create " + std::to_string(size.width) + "x" + std::to_string(size.height) + " failed (" +
            base::errno_text(errno) + ")";
    return false;
  }
  EGLSurface egl_surface = eglCreateWindowSurface(display_, config_, reinterpret_cast<EGLNativeWindowType>(surface), nullptr);
  if (egl_surface == EGL_NO_SURFACE || !eglMakeCurrent(display_, egl_surface, egl_surface, context_)) {
    error = "kms: no EGL window surface on the GBM surface (" + egl::error_name(eglGetError()) + ")";
    if (egl_surface != EGL_NO_SURFACE) eglDestroySurface(display_, egl_surface);
    gbm_surface_destroy(surface);
    return false;
  }
  // The old surface's buffers go back before its EGL surface (which frees them) and its GBM surface.
  release_all();
  if (egl_surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, egl_surface_);
  if (surface_ != nullptr) gbm_surface_destroy(surface_);
  surface_ = surface;
  egl_surface_ = egl_surface;
  size_ = size;
  return true;
}

gbm_bo* Surface::swap(std::string& error) {
  if (!eglSwapBuffers(display_, egl_surface_)) {
    error = "kms: eglSwapBuffers failed (" + egl::error_name(eglGetError()) + ")";
    return nullptr;
  }
  gbm_bo* bo = gbm_surface_lock_front_buffer(surface_);
  if (bo == nullptr) error = "kms: no front buffer after eglSwapBuffers (gbm_surface_lock_front_buffer)";
  return bo;
}

std::uint32_t Surface::framebuffer_for(gbm_bo* bo, std::string& error) {
  if (auto* cached = static_cast<FbData*>(gbm_bo_get_user_data(bo))) return cached->fb;
  std::uint32_t handles[4] = {}, strides[4] = {}, offsets[4] = {};
  std::uint64_t modifiers[4] = {};
  const int planes = std::clamp(gbm_bo_get_plane_count(bo), 1, 4);
  const std::uint64_t modifier = gbm_bo_get_modifier(bo);
  for (int p = 0; p < planes; ++p) {
    handles[p] = gbm_bo_get_handle_for_plane(bo, p).u32;
    strides[p] = gbm_bo_get_stride_for_plane(bo, p);
    offsets[p] = gbm_bo_get_offset(bo, p);
    modifiers[p] = modifier;
  }
  const std::uint32_t width = gbm_bo_get_width(bo), height = gbm_bo_get_height(bo), format = gbm_bo_get_format(bo);
  const bool with_modifier = modifiers_ && modifier != DRM_FORMAT_MOD_INVALID;
  std::uint32_t fb = 0;
  const int result = with_modifier ? drmModeAddFB2WithModifiers(fd_, width, height, format, handles, strides, offsets, modifiers,
                                                                &fb, DRM_MODE_FB_MODIFIERS)
                                   : drmModeAddFB2(fd_, width, height, format, handles, strides, offsets, &fb, 0);
  if (result != 0) {
    char fourcc[5] = {static_cast<char>(format), static_cast<char>(format >> 8), static_cast<char>(format >> 16),
                      static_cast<char>(format >> 24), '\0'};
    char modifier_text[32];
    std::snprintf(modifier_text, sizeof modifier_text, "0x%016llx", static_cast<unsigned long long>(modifier));
    error = "kms: " + device_path_ + " refused a " + std::to_string(width) + "x" + std::to_string(height) + " " + fourcc +
            " framebuffer with " + std::to_string(planes) + " plane(s), " +
            (with_modifier ? std::string("modifier ") + modifier_text : std::string("no modifier")) +
            " (drmModeAddFB2: " + base::errno_text(errno) + ")";
    return 0;
  }
  gbm_bo_set_user_data(bo, new FbData{fd_, fb}, destroy_fb);
  return fb;
}

void Surface::release(gbm_bo* bo) {
  gbm_surface_release_buffer(surface_, bo);
}

void Surface::flip_completed() {
  if (shown_ != nullptr) release(shown_);
  shown_ = pending_;
  pending_ = nullptr;
}

void Surface::shown_by_modeset(gbm_bo* bo) {
  release_all();
  shown_ = bo;
}

void Surface::release_all() {
  if (surface_ == nullptr) return;
  if (pending_ != nullptr) release(pending_);
  if (shown_ != nullptr) release(shown_);
  pending_ = shown_ = nullptr;
}

}  // namespace platform::kms
