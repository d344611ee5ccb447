#pragma once
// What the EGL-based platforms (headless egl, kms on GBM) share.
#include <EGL/egl.h>

#include <string>

namespace platform::egl {

// Whether the space-separated extension list names `name` exactly.
bool has_extension(const char* list, const char* name);
std::string error_name(EGLint code);

// eglInitialize and eglBindAPI(EGL_OPENGL_ES_API); false and why otherwise.
bool initialize(EGLDisplay display, EGLint& major, EGLint& minor, std::string& why);
// An OpenGL ES 3.1 context for `config` (a KHR_debug context when asked and EGL 1.5 offers it);
// EGL_NO_CONTEXT and why otherwise.
EGLContext create_context(EGLDisplay display, EGLConfig config, EGLint major, EGLint minor, bool debug, std::string& why);

}  // namespace platform::egl
