#include "backends.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include "egl_util.h"

#include <cstring>
#include <string>

namespace platform {
namespace {

using egl::error_name;
using egl::has_extension;

// A headless surface: a pbuffer of the requested size, sRGB-encoding where EGL_KHR_gl_colorspace
// lets it be, so the present pass writes linear colour as a display's framebuffer would take it.
class EglPlatform final : public Platform {
 public:
  EglPlatform(EGLDisplay display, EGLConfig config, EGLContext context, bool colorspace, std::string how,
              std::vector<std::string> used)
      : display_(display),
        config_(config),
        context_(context),
        colorspace_(colorspace),
        how_(std::move(how)),
        used_(std::move(used)) {}
  // The display is not terminated: an EGLDisplay is one per device and process, shared by every
  // Platform made on it, so terminating it here would pull it from under another. (Mesa also unloads
  // its driver on eglTerminate, which leaves LeakSanitizer unable to name the driver's allocations.)
  ~EglPlatform() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
    eglDestroyContext(display_, context_);
  }
  std::string_view name() const override { return "egl"; }
  std::string description() const override { return how_ + (srgb_ ? ", sRGB pbuffer" : ", pbuffer"); }
  std::vector<std::string> extensions_used() const override { return used_; }
  void* proc_address(const char* name) const override { return reinterpret_cast<void*>(eglGetProcAddress(name)); }
  Size size() const override { return size_; }
  unsigned framebuffer() const override { return 0; }
  bool srgb_framebuffer() const override { return srgb_; }
  bool present() override { return true; }

  bool resize(Size size, std::string& error) override {
    if (size == size_ && surface_ != EGL_NO_SURFACE) return true;
    EGLSurface surface = EGL_NO_SURFACE;
    bool srgb = false;
    if (colorspace_) {
      const EGLint attributes[] = {
          EGL_WIDTH, size.width, EGL_HEIGHT, size.height, EGL_GL_COLORSPACE_KHR, EGL_GL_COLORSPACE_SRGB_KHR, EGL_NONE};
      surface = eglCreatePbufferSurface(display_, config_, attributes);
      srgb = surface != EGL_NO_SURFACE;
    }
    if (surface == EGL_NO_SURFACE) {
      const EGLint attributes[] = {EGL_WIDTH, size.width, EGL_HEIGHT, size.height, EGL_NONE};
      surface = eglCreatePbufferSurface(display_, config_, attributes);
    }
    if (surface == EGL_NO_SURFACE) {
      error = "egl: no pbuffer of " + std::to_string(size.width) + "x" + std::to_string(size.height) + " (" +
              error_name(eglGetError()) + ")";
      return false;
    }
    if (!eglMakeCurrent(display_, surface, surface, context_)) {
      error = "egl: eglMakeCurrent on the pbuffer failed (" + error_name(eglGetError()) + ")";
      eglDestroySurface(display_, surface);
      return false;
    }
    if (surface_ != EGL_NO_SURFACE) eglDestroySurface(display_, surface_);
    surface_ = surface;
    size_ = size;
    srgb_ = srgb;
    return true;
  }

 private:
  EGLDisplay display_;
  EGLConfig config_;
  EGLContext context_;
  EGLSurface surface_ = EGL_NO_SURFACE;
  bool colorspace_ = false, srgb_ = false;
  Size size_;
  std::string how_;
  std::vector<std::string> used_;
};

struct Made {
  EGLConfig config = nullptr;
  EGLContext context = EGL_NO_CONTEXT;
  bool colorspace = false;
};

// Makes a GLES 3.1 context for an RGBA8 pbuffer. Returns EGL_NO_CONTEXT and says why otherwise.
Made make_context(EGLDisplay display, bool debug, std::string& why) {
  Made made;
  EGLint major = 0, minor = 0;
  if (!egl::initialize(display, major, minor, why)) return made;
  const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
  EGLConfig config = nullptr;
  const EGLint wanted[] = {EGL_RENDERABLE_TYPE,
                           EGL_OPENGL_ES3_BIT_KHR,
                           EGL_SURFACE_TYPE,
                           EGL_PBUFFER_BIT,
                           EGL_RED_SIZE,
                           8,
                           EGL_GREEN_SIZE,
                           8,
                           EGL_BLUE_SIZE,
                           8,
                           EGL_ALPHA_SIZE,
                           8,
                           EGL_NONE};
  EGLint count = 0;
  if (!eglChooseConfig(display, wanted, &config, 1, &count) || count < 1) {
    why = "no EGL config renders OpenGL ES 3 into an RGBA8 pbuffer";
    return made;
  }
  EGLContext context = egl::create_context(display, config, major, minor, debug, why);
  if (context == EGL_NO_CONTEXT) return made;
  made.config = config;
  made.context = context;
  made.colorspace = has_extension(extensions, "EGL_KHR_gl_colorspace");
  return made;
}

// Hands the display and context to a Platform and makes its pbuffer current.
std::unique_ptr<Platform> finish(EGLDisplay display, const Made& made, std::string how, std::vector<std::string> used,
                                 const Options& options, std::string& error) {
  if (made.colorspace) used.push_back("EGL_KHR_gl_colorspace");
  auto platform =
      std::make_unique<EglPlatform>(display, made.config, made.context, made.colorspace, std::move(how), std::move(used));
  if (!platform->resize(options.size, error)) return nullptr;  // the Platform's destructor releases the context
  return platform;
}

}  // namespace

std::unique_ptr<Platform> create_egl(const Options& options, std::string& error) {
  const bool debug = options.debug_context;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_extension(client, "EGL_EXT_platform_base")) {
    error = "egl: the EGL library lacks EGL_EXT_platform_base, so no headless display can be opened";
    return nullptr;
  }
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  std::string attempts;

  // A real GPU (the NVIDIA driver exposes devices, not a surfaceless platform).
  if (has_extension(client, "EGL_EXT_platform_device") && has_extension(client, "EGL_EXT_device_enumeration")) {
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto query_device_string = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
    EGLDeviceEXT devices[16];
    EGLint count = 0;
    if (query_devices && query_devices(16, devices, &count)) {
      for (EGLint i = 0; i < count; ++i) {
        const char* device_extensions = query_device_string ? query_device_string(devices[i], EGL_EXTENSIONS) : nullptr;
        // Mesa lists its software rasteriser as a device too; surfaceless below is the same thing.
        if (has_extension(device_extensions, "EGL_MESA_device_software")) continue;
        EGLDisplay display = get_platform_display(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
        if (display == EGL_NO_DISPLAY) continue;
        std::string why;
        const Made made = make_context(display, debug, why);
        if (made.context != EGL_NO_CONTEXT)
          return finish(display, made, "EGL_EXT_platform_device (device " + std::to_string(i) + ")",
                        {"EGL_EXT_platform_device", "EGL_EXT_device_enumeration"}, options, error);
        attempts += "; device " + std::to_string(i) + ": " + why;
      }
    }
  }

  if (has_extension(client, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display != EGL_NO_DISPLAY) {
      std::string why;
      const Made made = make_context(display, debug, why);
      if (made.context != EGL_NO_CONTEXT)
        return finish(display, made, "EGL_MESA_platform_surfaceless", {"EGL_MESA_platform_surfaceless"}, options, error);
      attempts += "; surfaceless: " + why;
    }
  } else {
    attempts += "; EGL_MESA_platform_surfaceless not offered";
  }
  error = "egl: no headless OpenGL ES 3.1 context could be made" + attempts +
          " (try --platform osmesa, or install libegl-mesa0 and libgl1-mesa-dri)";
  return nullptr;
}

}  // namespace platform
