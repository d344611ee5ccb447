#include "platform/backends.h"

#include "gl/gl_api.h"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstring>
#include <string>

namespace platform {
namespace {

bool has_extension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const size_t length = std::strlen(name);
  for (const char* at = std::strstr(list, name); at != nullptr; at = std::strstr(at + 1, name))
    if ((at == list || at[-1] == ' ') && (at[length] == ' ' || at[length] == '\0')) return true;
  return false;
}

void* egl_proc(const char* name, void*) { return reinterpret_cast<void*>(eglGetProcAddress(name)); }

std::string egl_error_name(EGLint code) {
  switch (code) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    default: return "EGL error 0x" + std::to_string(code);
  }
}

class EglPlatform final : public Platform {
 public:
  EglPlatform(EGLDisplay display, EGLContext context, std::string how, std::vector<std::string> used)
      : display_(display), context_(context), how_(std::move(how)), used_(std::move(used)) {}
  // The display is not terminated: an EGLDisplay is one per device and process, shared by every
  // Platform made on it, so terminating it here would pull it from under another. (Mesa also unloads
  // its driver on eglTerminate, which leaves LeakSanitizer unable to name the driver's allocations.)
  ~EglPlatform() override {
    eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    eglDestroyContext(display_, context_);
  }
  std::string_view name() const override { return "egl"; }
  std::string description() const override { return how_; }
  std::vector<std::string> extensions_used() const override { return used_; }

 private:
  EGLDisplay display_;
  EGLContext context_;
  std::string how_;
  std::vector<std::string> used_;
};

// Makes a GLES 3.1 context current with no surface. Returns EGL_NO_CONTEXT and says why otherwise.
EGLContext make_context(EGLDisplay display, bool debug, std::string& why) {
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) {
    why = "eglInitialize failed (" + egl_error_name(eglGetError()) + ")";
    return EGL_NO_CONTEXT;
  }
  const char* extensions = eglQueryString(display, EGL_EXTENSIONS);
  if (!has_extension(extensions, "EGL_KHR_surfaceless_context")) {
    why = "the display lacks EGL_KHR_surfaceless_context";
    return EGL_NO_CONTEXT;
  }
  if (!eglBindAPI(EGL_OPENGL_ES_API)) {
    why = "eglBindAPI(EGL_OPENGL_ES_API) failed";
    return EGL_NO_CONTEXT;
  }
  EGLConfig config = EGL_NO_CONFIG_KHR;
  if (!has_extension(extensions, "EGL_KHR_no_config_context")) {
    const EGLint wanted[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT_KHR, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
    EGLint count = 0;
    if (!eglChooseConfig(display, wanted, &config, 1, &count) || count < 1) {
      why = "no EGL config renders OpenGL ES 3";
      return EGL_NO_CONTEXT;
    }
  }
  const bool debug_ok = debug && (major > 1 || minor >= 5);
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 1,
                               debug_ok ? EGL_CONTEXT_OPENGL_DEBUG : EGL_NONE, EGL_TRUE, EGL_NONE};
  EGLContext context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT) {
    why = "eglCreateContext for OpenGL ES 3.1 failed (" + egl_error_name(eglGetError()) + ")";
    return EGL_NO_CONTEXT;
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    why = "eglMakeCurrent without a surface failed (" + egl_error_name(eglGetError()) + ")";
    eglDestroyContext(display, context);
    return EGL_NO_CONTEXT;
  }
  return context;
}

// With a context current: loads the GL entry points and hands the display and context to a Platform.
std::unique_ptr<Platform> finish(EGLDisplay display, EGLContext context, std::string how,
                                 std::vector<std::string> used, std::string& error) {
  auto platform = std::make_unique<EglPlatform>(display, context, std::move(how), std::move(used));
  std::string load_error;
  if (!gl::load(egl_proc, nullptr, load_error)) {
    error = "egl: " + load_error;
    return nullptr;  // the Platform's destructor releases the context
  }
  return platform;
}

}  // namespace

std::unique_ptr<Platform> create_egl(bool debug, std::string& error) {
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_extension(client, "EGL_EXT_platform_base")) {
    error = "egl: the EGL library lacks EGL_EXT_platform_base, so no headless display can be opened";
    return nullptr;
  }
  auto get_platform_display =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  std::string attempts;

  // A real GPU (the NVIDIA driver exposes devices, not a surfaceless platform).
  if (has_extension(client, "EGL_EXT_platform_device") && has_extension(client, "EGL_EXT_device_enumeration")) {
    auto query_devices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
    auto query_device_string =
        reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
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
        EGLContext context = make_context(display, debug, why);
        if (context != EGL_NO_CONTEXT)
          return finish(display, context, "EGL_EXT_platform_device (device " + std::to_string(i) + ")",
                        {"EGL_EXT_platform_device", "EGL_EXT_device_enumeration", "EGL_KHR_surfaceless_context"},
                        error);
        attempts += "; device " + std::to_string(i) + ": " + why;
      }
    }
  }

  if (has_extension(client, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay display = get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display != EGL_NO_DISPLAY) {
      std::string why;
      EGLContext context = make_context(display, debug, why);
      if (context != EGL_NO_CONTEXT)
        return finish(display, context, "EGL_MESA_platform_surfaceless",
                      {"EGL_MESA_platform_surfaceless", "EGL_KHR_surfaceless_context"}, error);
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
