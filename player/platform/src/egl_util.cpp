#include "egl_util.h"

#include <EGL/eglext.h>

#include <cstring>

namespace platform::egl {

bool has_extension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const size_t length = std::strlen(name);
  for (const char* at = std::strstr(list, name); at != nullptr; at = std::strstr(at + 1, name))
    if ((at == list || at[-1] == ' ') && (at[length] == ' ' || at[length] == '\0')) return true;
  return false;
}

std::string error_name(EGLint code) {
  switch (code) {
    case EGL_SUCCESS:
      return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED:
      return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS:
      return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC:
      return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE:
      return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG:
      return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT:
      return "EGL_BAD_CONTEXT";
    case EGL_BAD_DISPLAY:
      return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH:
      return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER:
      return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE:
      return "EGL_BAD_SURFACE";
    case EGL_BAD_NATIVE_WINDOW:
      return "EGL_BAD_NATIVE_WINDOW";
    case EGL_CONTEXT_LOST:
      return "EGL_CONTEXT_LOST";
    default:
      return "EGL error 0x" + std::to_string(code);
  }
}

bool initialize(EGLDisplay display, EGLint& major, EGLint& minor, std::string& why) {
  if (!eglInitialize(display, &major, &minor)) {
    why = "eglInitialize failed (" + error_name(eglGetError()) + ")";
    return false;
  }
  if (!eglBindAPI(EGL_OPENGL_ES_API)) {
    why = "eglBindAPI(EGL_OPENGL_ES_API) failed";
    return false;
  }
  return true;
}

EGLContext create_context(EGLDisplay display, EGLConfig config, EGLint major, EGLint minor, bool debug, std::string& why) {
  const bool debug_ok = debug && (major > 1 || minor >= 5);
  EGLContext context = EGL_NO_CONTEXT;
  // A context that is told of GPU resets, so the player can rebuild after one instead of drawing
  // nothing; where the driver cannot make one, a plain context.
  if (has_extension(eglQueryString(display, EGL_EXTENSIONS), "EGL_EXT_create_context_robustness")) {
    const EGLint robust[] = {EGL_CONTEXT_MAJOR_VERSION,
                             3,
                             EGL_CONTEXT_MINOR_VERSION,
                             1,
                             EGL_CONTEXT_OPENGL_RESET_NOTIFICATION_STRATEGY_EXT,
                             EGL_LOSE_CONTEXT_ON_RESET_EXT,
                             debug_ok ? EGL_CONTEXT_OPENGL_DEBUG : EGL_NONE,
                             EGL_TRUE,
                             EGL_NONE};
    context = eglCreateContext(display, config, EGL_NO_CONTEXT, robust);
  }
  const EGLint attributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                               3,
                               EGL_CONTEXT_MINOR_VERSION,
                               1,
                               debug_ok ? EGL_CONTEXT_OPENGL_DEBUG : EGL_NONE,
                               EGL_TRUE,
                               EGL_NONE};
  if (context == EGL_NO_CONTEXT) context = eglCreateContext(display, config, EGL_NO_CONTEXT, attributes);
  if (context == EGL_NO_CONTEXT) why = "eglCreateContext for OpenGL ES 3.1 failed (" + error_name(eglGetError()) + ")";
  return context;
}

}  // namespace platform::egl
