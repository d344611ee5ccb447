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

// What a platform receives besides frames: window keys, resize and close, a display that comes or
// goes (kms hotplug, DRM master lost and back). Plain data, so draining events allocates nothing.
// `warning`: something the player should report once (a refused commit); last_error() says what.
// `remake`: this platform cannot go on and a new one (and context) would (kms: DRM master can only be
// had again through a new open of the device); last_error() says why.
enum class EventType : std::uint8_t {
  key_press,
  key_release,
  resized,
  close_requested,
  display_lost,
  display_found,
  warning,
  remake
};

struct Event {
  EventType type = EventType::close_requested;
  char key[24] = {};  // key_press/key_release: the key's name as board files write it ("space", "n", "f11")
  Size size;          // resized, display_found: the new surface size
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

  // False while frames cannot be shown (kms: no display connected, another process holds the
  // display); the player then draws nothing, keeps its clock, and waits on event_fd() for at most
  // poll_interval_ms() before draining events again. not_presenting_reason() says why.
  virtual bool presenting() const { return true; }
  virtual std::string not_presenting_reason() const { return {}; }
  virtual int poll_interval_ms() const { return 100; }
  // Switches the display off (outside opening hours) or on again. Off: present() shows nothing until
  // it is on; kms switches the CRTC off (atomic ACTIVE, legacy DPMS) and sets the mode again when on.
  // `state` says what the hardware reports afterwards, for the log ("CRTC 37 ACTIVE=0"). Platforms
  // without a display of their own (a window, a pbuffer) have nothing to switch: true and nothing done.
  virtual bool set_display_power(bool on, std::string& state, std::string& error) {
    (void)on;
    (void)error;
    state = std::string(name()) + ": no display of its own to switch";
    return true;
  }
  // The last error of present(): why it returned false.
  virtual std::string last_error() const { return {}; }

  // What the display shows now, read back from the hardware's output (kms: a writeback connector),
  // as top-down RGBA8. False and why where the platform or the driver cannot.
  virtual bool capture_scanout(std::vector<std::uint8_t>& rgba, Size& size, std::string& error) {
    (void)rgba;
    (void)size;
    error = std::string(name()) + ": cannot capture what the display shows (only kms with a writeback connector can)";
    return false;
  }
};

struct Options {
  // A registry name, or "auto": with `display` the platform for a screen (see choose_auto), without it
  // the first headless one that works.
  std::string_view name = "auto";
  bool display = false;     // the caller shows frames (play), rather than reading them back (render)
  Size size{1024, 768};     // the surface to make; a window's initial size; kms: the size while no display is connected
  bool fullscreen = false;  // window: start fullscreen
  bool debug_context = false;
  // kms, as mpv names them: the DRM node (empty: the first with KMS and a connected display), the
  // connector (auto, or a name such as HDMI-A-1), the mode (preferred, highest, WxH[@R]) and whether
  // atomic modesetting is used where the driver offers it (auto, no).
  std::string drm_device;
  std::string drm_connector = "auto";
  std::string drm_mode = "preferred";
  std::string drm_atomic = "auto";
};

// What a platform is, for the choices a caller makes before (or without) opening it.
struct Capabilities {
  // Frames go to a screen a person watches, so they are paced by it and the playlist runs on real
  // time; without, frames are read back and a run can step a reproducible manual clock.
  bool shows_frames_on_a_display = false;
  // A window among others on a desktop, with no board beside it: the board's LEDs and state are
  // drawn over the frame unless asked otherwise (play --overlay auto).
  bool desktop_window = false;
};

// One row per platform; the only place platforms are listed.
struct Entry {
  std::string_view name;
  std::string_view summary;  // for --help
  bool tried_by_auto;        // headless ones are; a window is only made when asked for
  std::unique_ptr<Platform> (*create)(const Options& options, std::string& error);
  Capabilities capabilities;
};
std::span<const Entry> registry();
// The registry row's capabilities of `name`; an unknown name has none (create() then says why).
Capabilities capabilities(std::string_view name);

// For "auto" with `display`: kms where a DRM device with KMS exists and no display server runs
// (neither WAYLAND_DISPLAY nor DISPLAY is set), window where one runs, egl otherwise. `why` says which
// rule chose it, for the first status line.
std::string_view choose_auto(std::string& why);

// The kms connectors of `options.drm_device` (or of every DRM device when empty) with their state and
// modes, for --drm-connector help. False and why when no device can be opened.
bool describe_kms_outputs(const Options& options, std::string& text, std::string& error);

// Creates a context with its surface and makes it current on this thread (then call gl::load).
// Returns null and says why in `error` when the platform is unknown or nothing could be made.
std::unique_ptr<Platform> create(const Options& options, std::string& error);

// "auto" and every registry name, for option checks and messages.
std::vector<std::string> names();
// "auto, kms, egl, osmesa or window", for --help and error messages.
std::string names_text();

}  // namespace platform
