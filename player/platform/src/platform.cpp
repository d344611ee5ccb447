#include "backends.h"

#include <cstdlib>

namespace platform {
namespace {

constexpr Entry kRegistry[] = {
    {"egl", "headless EGL: EGL_EXT_platform_device for GPUs, else Mesa's surfaceless platform", true, create_egl, {}},
    {"osmesa", "Mesa's OSMesa, desktop GL 4.5 core running the same ES 3.1 shaders", true, create_osmesa, {}},
    {"window",
     "a desktop window (SDL2, X11 or Wayland) with OpenGL ES 3.1 on EGL; F11 toggles fullscreen",
     false,
     create_window,
     {.shows_frames_on_a_display = true, .desktop_window = true}},
    {"kms",
     "fullscreen on a display through DRM/KMS and EGL on GBM, no display server (the board default)",
     false,
     create_kms,
     {.shows_frames_on_a_display = true, .desktop_window = false}},
};

}  // namespace

std::span<const Entry> registry() {
  return kRegistry;
}

Capabilities capabilities(std::string_view name) {
  for (const Entry& entry : registry())
    if (entry.name == name) return entry.capabilities;
  return {};
}

std::vector<std::string> names() {
  std::vector<std::string> all{"auto"};
  for (const Entry& entry : registry()) all.emplace_back(entry.name);
  return all;
}

std::string names_text() {
  const std::vector<std::string> all = names();
  std::string text;
  for (size_t i = 0; i < all.size(); ++i) text += (i == 0 ? "" : i + 1 == all.size() ? " or " : ", ") + all[i];
  return text;
}

std::unique_ptr<Platform> create(const Options& options, std::string& error) {
  if (options.size.width < 1 || options.size.height < 1) {
    error = "--size: " + std::to_string(options.size.width) + "x" + std::to_string(options.size.height) +
            " is not a surface size (expected positive width and height)";
    return nullptr;
  }
  if (options.name == "auto" && options.display) {
    std::string why;
    const std::string_view chosen = choose_auto(why);
    Options resolved = options;
    resolved.name = chosen;
    if (auto platform = create(resolved, error)) return platform;
    error += " (platform " + std::string(chosen) + " chosen because " + why + "; --platform chooses another)";
    return nullptr;
  }
  if (options.name == "auto") {
    std::string attempts;
    for (const Entry& entry : registry()) {
      if (!entry.tried_by_auto) continue;
      std::string why;
      if (auto platform = entry.create(options, why)) return platform;
      attempts += (attempts.empty() ? "" : "; ") + why;
    }
    error = attempts;
    return nullptr;
  }
  for (const Entry& entry : registry())
    if (entry.name == options.name) return entry.create(options, error);
  error = "--platform: unknown platform '" + std::string(options.name) + "' (expected " + names_text() + ")";
  return nullptr;
}

std::string_view choose_auto(std::string& why) {
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  const char* x11 = std::getenv("DISPLAY");
  if ((wayland != nullptr && *wayland != '\0') || (x11 != nullptr && *x11 != '\0')) {
    why = std::string("a display server runs (") + (wayland != nullptr && *wayland != '\0' ? "WAYLAND_DISPLAY" : "DISPLAY") +
          " is set)";
    return "window";
  }
  std::string device;
  if (find_kms_device(device)) {
    why = device + " drives displays (KMS) and no display server runs";
    return "kms";
  }
  why = "no display server runs and no DRM device drives a display";
  return "egl";
}

}  // namespace platform
