#pragma once
// What the current context can do, queried once after the entry points are loaded.
#include <string>
#include <vector>

namespace gl {

struct Caps {
  std::string renderer, version, shading_language;
  bool desktop_gl = false;    // desktop core profile running ES 3.1 shaders (OSMesa)
  bool timer_query = false;   // EXT_disjoint_timer_query (GLES) or ARB_timer_query / GL 3.3 (desktop)
  bool debug_output = false;  // KHR_debug
  // The context tells of a GPU reset (KHR/EXT_robustness, made with lose-context-on-reset): after one,
  // GetGraphicsResetStatus answers non-zero and every object of the context is gone.
  bool reset_notification = false;
  int max_compute_work_group_invocations = 0;
  int max_texture_size = 0;
  std::vector<std::string> extensions;

  bool has(const char* extension) const;
  // The extensions this player relies on, present or not, for `player info`.
  std::vector<std::pair<std::string, bool>> extensions_used() const;
};

// Reads the strings and limits of the current context. Clears optional entry points in gl::api
// whose extension is not advertised: some loaders hand out stubs for any name.
Caps query_caps();

// Routes KHR_debug messages to stderr; in release builds only when `enabled` is true.
void install_debug_log(const Caps& caps, bool enabled);

}  // namespace gl
