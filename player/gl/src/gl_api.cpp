#include "gl/gl_api.h"

namespace gl {

Api api;

bool load(const platform::Platform& platform, std::string& error) {
  const auto loader = [&platform](const char* symbol) { return platform.proc_address(symbol); };
  const std::string platform_name(platform.name());
  api = Api{};
  bool ok = true;
#define PLAYER_GL_LOAD_REQUIRED(type, name)                                             \
  api.name = reinterpret_cast<type>(loader("gl" #name));                                \
  if (ok && api.name == nullptr) {                                                      \
    error = platform_name + ": the GL context lacks the required entry point gl" #name; \
    ok = false;                                                                         \
  }
  PLAYER_GL_REQUIRED(PLAYER_GL_LOAD_REQUIRED)
#undef PLAYER_GL_LOAD_REQUIRED
  // Desktop GL has these in core; GLES only through EXT_disjoint_timer_query and KHR_debug.
  for (const char* suffix : {"", "EXT", "KHR"}) {
#define PLAYER_GL_LOAD_OPTIONAL(type, name) \
  if (api.name == nullptr) api.name = reinterpret_cast<type>(loader((std::string("gl" #name) + suffix).c_str()));
    PLAYER_GL_OPTIONAL(PLAYER_GL_LOAD_OPTIONAL)
#undef PLAYER_GL_LOAD_OPTIONAL
  }
  return ok;
}

}  // namespace gl
