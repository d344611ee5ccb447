#include "gl/caps.h"

#include "gl/gl_api.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

namespace gl {
namespace {

std::string string_of(GLenum name) {
  const GLubyte* value = api.GetString(name);
  return value ? reinterpret_cast<const char*>(value) : "";
}

void GL_APIENTRY log_debug_message(GLenum, GLenum type, GLuint id, GLenum severity, GLsizei, const GLchar* message, const void*) {
  if (severity == GL_DEBUG_SEVERITY_NOTIFICATION_KHR) return;
  std::fprintf(stderr, "gl debug [type 0x%x, id %u, severity 0x%x]: %s\n", type, id, severity, message);
}

}  // namespace

bool Caps::has(const char* extension) const {
  return std::find(extensions.begin(), extensions.end(), extension) != extensions.end();
}

std::vector<std::pair<std::string, bool>> Caps::extensions_used() const {
  std::vector<std::pair<std::string, bool>> used;
  if (desktop_gl) {
    used = {{"GL_ARB_ES3_1_compatibility", has("GL_ARB_ES3_1_compatibility")},
            {"GL_ARB_timer_query", timer_query},
            {"GL_KHR_debug", debug_output},
            {"GL_KHR_robustness", reset_notification}};
  } else {
    used = {
        {"GL_EXT_disjoint_timer_query", timer_query},
        {"GL_KHR_debug", debug_output},
        {has("GL_EXT_robustness") && !has("GL_KHR_robustness") ? "GL_EXT_robustness" : "GL_KHR_robustness", reset_notification}};
  }
  return used;
}

Caps query_caps() {
  Caps caps;
  caps.renderer = string_of(GL_RENDERER);
  caps.version = string_of(GL_VERSION);
  caps.shading_language = string_of(GL_SHADING_LANGUAGE_VERSION);
  caps.desktop_gl = caps.version.rfind("OpenGL ES", 0) != 0;
  GLint count = 0;
  api.GetIntegerv(GL_NUM_EXTENSIONS, &count);
  for (GLint i = 0; i < count; ++i) {
    const GLubyte* name = api.GetStringi(GL_EXTENSIONS, static_cast<GLuint>(i));
    if (name) caps.extensions.emplace_back(reinterpret_cast<const char*>(name));
  }
  // Desktop GL 3.3+ has timer queries and GL 4.3+ KHR_debug in core.
  caps.timer_query = caps.desktop_gl ? true : caps.has("GL_EXT_disjoint_timer_query");
  caps.debug_output = caps.desktop_gl ? true : caps.has("GL_KHR_debug");
  if (!caps.timer_query || !api.QueryCounter || !api.GetQueryObjectui64v) {
    caps.timer_query = false;
    api.QueryCounter = nullptr;
    api.GetQueryObjectui64v = nullptr;
  }
  if (!caps.debug_output || !api.DebugMessageCallback) {
    caps.debug_output = false;
    api.DebugMessageCallback = nullptr;
    api.DebugMessageControl = nullptr;
  }
  // Reset notification needs the extension (core in desktop GL 4.5) and a context made to lose itself
  // on reset; anything else never answers anything but GL_NO_ERROR.
  const bool robustness = caps.desktop_gl || caps.has("GL_KHR_robustness") || caps.has("GL_EXT_robustness");
  GLint strategy = 0;
  if (robustness && api.GetGraphicsResetStatus != nullptr) api.GetIntegerv(GL_RESET_NOTIFICATION_STRATEGY_KHR, &strategy);
  caps.reset_notification = strategy == GL_LOSE_CONTEXT_ON_RESET_KHR;
  if (!caps.reset_notification) api.GetGraphicsResetStatus = nullptr;
  api.GetIntegerv(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS, &caps.max_compute_work_group_invocations);
  api.GetIntegerv(GL_MAX_TEXTURE_SIZE, &caps.max_texture_size);
  return caps;
}

void install_debug_log(const Caps& caps, bool enabled) {
#ifndef NDEBUG
  enabled = true;
#endif
  if (!enabled || !caps.debug_output) return;
  api.Enable(GL_DEBUG_OUTPUT_KHR);
  api.Enable(GL_DEBUG_OUTPUT_SYNCHRONOUS_KHR);  // messages arrive inside the call that caused them
  api.DebugMessageCallback(log_debug_message, nullptr);
}

}  // namespace gl
