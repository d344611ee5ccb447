#pragma once
// Context and presentation surface, one interface for every way the player gets GL and shows a
// frame: headless EGL (device or Mesa surfaceless, on a pbuffer), OSMesa, a desktop window. The
// render code is the same on each: it draws into framebuffer() at size(), then calls present().
//
// Errors: creation returns null and says why in `error`; once running nothing throws, and
// present() reports failure by its return value.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace platform {

struct Size {
  int width = 0, height = 0;
  bool operator==(const Size&) const = default;
};

// What a platform receives besides frames: window keys, resize and close (later page flips and
// hotplug). Plain data, so draining events allocates nothing.
enum class EventType : std::uint8_t { key_press, key_release, resized, close_requested };

struct Event {
  EventType type = EventType::close_requested;
  char key[24] = {};  // key_press/key_release: the key's name as board files write it ("space", "n", "f11")
  Size size;          // resized: the new surface size
};

class Platform {
 public:
  virtual ~Platform() = default;
  virtual std::string_view name() const = 0;  // the registry name: "egl", "osmesa", "window"
  // How the context was made, e.g. "EGL_EXT_platform_device (device 0)".
  virtual std::string description() const = 0;
  // Window-system extensions this platform relied on, for `player info`.
  virtual std::vector<std::string> extensions_used() const = 0;
  // For gl::load: the GL entry point of the current context, or null.
  virtual void* proc_address(const char* name) const = 0;

  // The surface frames are presented on, in pixels.
  virtual Size size() const = 0;
  // The GL framebuffer name to draw the presented image into; 0 for a window, a scanout or a pbuffer.
  virtual unsigned framebuffer() const = 0;
  // True when the framebuffer encodes linear colour to sRGB itself on write; otherwise the present
  // pass encodes in the shader.
  virtual bool srgb_framebuffer() const = 0;
  // Headless platforms reallocate their surface; a window asks the window system (the answer
  // arrives as a `resized` event). Returns false and says why.
  virtual bool resize(Size size, std::string& error) = 0;
  // Shows the frame drawn into framebuffer() (a swap; nothing for a headless surface). Returns false
  // when the surface is gone.
  virtual bool present() = 0;

  // Readable when events are waiting; -1 for a platform that never has any. Events may also arrive
  // without the fd becoming readable (a window system's own queue), so a loop drains once per frame.
  virtual int event_fd() const { return -1; }
  // Copies up to out.size() pending events, oldest first. Never blocks or allocates.
  virtual std::size_t drain_events(std::span<Event> out) {
    (void)out;
    return 0;
  }
};

struct Options {
  std::string_view name = "auto";  // a registry name, or "auto" (the first that works, in registry order)
  Size size{1024, 768};            // the surface to make; a window's initial size
  bool fullscreen = false;         // window: start fullscreen
  bool debug_context = false;
};

// One row per platform; the only place platforms are listed.
struct Entry {
  std::string_view name;
  std::string_view summary;  // for --help
  bool tried_by_auto;        // headless ones are; a window is only made when asked for
  std::unique_ptr<Platform> (*create)(const Options& options, std::string& error);
};
std::span<const Entry> registry();

// Creates a context with its surface and makes it current on this thread (then call gl::load).
// Returns null and says why in `error` when the platform is unknown or nothing could be made.
std::unique_ptr<Platform> create(const Options& options, std::string& error);

// "auto" and every registry name, for option checks and messages.
std::vector<std::string> names();
// "auto, egl, osmesa or window", for --help and error messages.
std::string names_text();

}  // namespace platform
