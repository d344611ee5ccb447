#include "platform/backends.h"

namespace platform {

std::vector<std::string> names() { return {"auto", "egl", "osmesa"}; }

std::unique_ptr<Platform> create(const Options& options, std::string& error) {
  if (options.name == "egl") return create_egl(options.debug_context, error);
  if (options.name == "osmesa") return create_osmesa(options.debug_context, error);
  if (options.name == "auto") {
    std::string egl_error;
    if (auto egl = create_egl(options.debug_context, egl_error)) return egl;
    if (auto osmesa = create_osmesa(options.debug_context, error)) return osmesa;
    error = egl_error + "; " + error;
    return nullptr;
  }
  error = "--platform: unknown platform '" + std::string(options.name) + "' (expected auto, egl or osmesa)";
  return nullptr;
}

}  // namespace platform
