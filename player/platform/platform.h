#pragma once
// Context creation, one interface for every way the player gets GL: headless EGL (device or
// Mesa surfaceless) and OSMesa. The render code is the same on each; it draws into framebuffers.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace platform {

class Platform {
 public:
  virtual ~Platform() = default;
  virtual std::string_view name() const = 0;  // "egl" or "osmesa"
  // How the context was made, e.g. "EGL_EXT_platform_device (device 0)".
  virtual std::string description() const = 0;
  // Window-system extensions this platform relied on, for `player info`.
  virtual std::vector<std::string> extensions_used() const = 0;
};

struct Options {
  std::string_view name = "auto";  // "egl", "osmesa" or "auto" (egl, then osmesa)
  bool debug_context = false;
};

// Creates a context, makes it current on this thread and loads gl::api for it. Returns null and
// says why in `error` when the platform is unknown or no context could be made.
std::unique_ptr<Platform> create(const Options& options, std::string& error);

// The names `create` accepts, for --help and error messages.
std::vector<std::string> names();

}  // namespace platform
