#include "backends.h"

#include <SDL2/SDL.h>
// SDL_syswm.h pulls in Xlib (and its macros: None, Bool, Status, ...), so it stays in this file.
#include <SDL2/SDL_syswm.h>
#if defined(SDL_VIDEO_DRIVER_X11)
#include <X11/Xlib.h>
#endif

#include <array>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <string>

namespace platform {
namespace {

// From the GLES 3 headers, which the platform layer does not include.
constexpr unsigned kGlFramebuffer = 0x8D40, kGlBack = 0x0405, kGlColorEncoding = 0x8210, kGlSrgb = 0x8C40;
constexpr unsigned kGlNoError = 0;
using GetFramebufferAttachmentParameteriv = void (*)(unsigned target, unsigned attachment, unsigned pname, int* value);
using GetError = unsigned (*)();

// Whether framebuffer 0's back buffer encodes to sRGB, asked of the context SDL made (the sRGB
// request is only a request: SDL drops it where EGL_KHR_gl_colorspace is missing, and the config
// may ignore it). A query that is missing or fails answers false, so the shader encodes.
bool query_srgb_back_buffer() {
  auto get_attachment =
      reinterpret_cast<GetFramebufferAttachmentParameteriv>(SDL_GL_GetProcAddress("glGetFramebufferAttachmentParameteriv"));
  auto get_error = reinterpret_cast<GetError>(SDL_GL_GetProcAddress("glGetError"));
  if (get_attachment == nullptr || get_error == nullptr) return false;
  // A fresh context has no errors queued, and GL queues at most one per flag: a few reads empty it.
  for (int i = 0; i < 8 && get_error() != kGlNoError; ++i) {
  }
  int encoding = 0;
  get_attachment(kGlFramebuffer, kGlBack, kGlColorEncoding, &encoding);
  // A failed query leaves an error behind; take it, so the renderer's error checks do not see it.
  bool failed = false;
  for (int i = 0; i < 8 && get_error() != kGlNoError; ++i) failed = true;
  return !failed && static_cast<unsigned>(encoding) == kGlSrgb;
}

// The key's name as board files write it: SDL's name in lower case, spaces as '-' ("space", "f11",
// "left-shift"). Cut at a UTF-8 character boundary when it does not fit; always NUL-terminated.
void copy_key_name(const char* name, char (&key)[sizeof(Event::key)]) {
  size_t length = std::strlen(name);
  if (length >= sizeof key) {
    length = sizeof key - 1;
    while (length > 0 && (static_cast<unsigned char>(name[length]) & 0xC0) == 0x80) --length;
  }
  for (size_t i = 0; i < length; ++i) {
    const unsigned char c = static_cast<unsigned char>(name[i]);
    key[i] = c == ' ' ? '-' : c < 0x80 ? static_cast<char>(std::tolower(c)) : static_cast<char>(c);
  }
  key[length] = '\0';
}

// A desktop window from SDL2 with an OpenGL ES 3.1 context on EGL. SDL owns the window system; the
// rest of the player sees only this interface and the Event stream.
class WindowPlatform final : public Platform {
 public:
  WindowPlatform(SDL_Window* window, SDL_GLContext context, bool srgb, bool vsync)
      : window_(window), context_(context), srgb_(srgb), vsync_(vsync), window_id_(SDL_GetWindowID(window)) {
    SDL_SysWMinfo info;
    SDL_VERSION(&info.version);
    if (SDL_GetWindowWMInfo(window_, &info)) {
#if defined(SDL_VIDEO_DRIVER_X11)
      if (info.subsystem == SDL_SYSWM_X11) event_fd_ = ConnectionNumber(info.info.x11.display);
#endif
    }
  }
  ~WindowPlatform() override {
    SDL_GL_MakeCurrent(window_, nullptr);
    SDL_GL_DeleteContext(context_);
    SDL_DestroyWindow(window_);
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
  }

  std::string_view name() const override {
    return "window";
  }
  std::string description() const override {
    const char* driver = SDL_GetCurrentVideoDriver();
    return std::string("SDL2 ") + (driver ? driver : "unknown") + " window, OpenGL ES 3.1 via EGL" +
           (srgb_ ? ", sRGB framebuffer" : "") + (vsync_ ? ", vsync" : "");
  }
  std::vector<std::string> extensions_used() const override {
    std::vector<std::string> used{"SDL_GL_CONTEXT_PROFILE_ES"};
    const char* driver = SDL_GetCurrentVideoDriver();
    if (driver && std::strcmp(driver, "x11") == 0) used.emplace_back("SDL_HINT_VIDEO_X11_FORCE_EGL");
    if (srgb_) used.emplace_back("SDL_GL_FRAMEBUFFER_SRGB_CAPABLE (EGL_KHR_gl_colorspace)");
    if (vsync_) used.emplace_back("SDL_GL_SetSwapInterval");
    return used;
  }
  void* proc_address(const char* name) const override {
    return SDL_GL_GetProcAddress(name);
  }

  Size size() const override {
    Size size;
    SDL_GL_GetDrawableSize(window_, &size.width, &size.height);
    return size;
  }
  unsigned framebuffer() const override {
    return 0;
  }
  bool srgb_framebuffer() const override {
    return srgb_;
  }

  bool resize(Size size, std::string& error) override {
    if (closed_) {
      error = "window: the window was closed";
      return false;
    }
    SDL_SetWindowSize(window_, size.width, size.height);
    return true;
  }

  // After a close request the window is on its way out: nothing more is shown.
  bool present() override {
    if (closed_) return false;
    SDL_GL_SwapWindow(window_);
    return true;
  }

  // The X11 connection: readable when the server sent something. Xlib may already hold events it
  // read while doing other work, which leaves the fd quiet, so the loop drains once per frame
  // anyway. -1 on Wayland and elsewhere (the per-frame drain is then the only way in).
  int event_fd() const override {
    return event_fd_;
  }

  std::size_t drain_events(std::span<Event> out) override {
    SDL_PumpEvents();
    SDL_Event event;
    while (pending_ < ring_.size() && SDL_PeepEvents(&event, 1, SDL_GETEVENT, SDL_FIRSTEVENT, SDL_LASTEVENT) == 1) convert(event);
    std::size_t copied = 0;
    for (; copied < out.size() && pending_ > 0; ++copied) {
      out[copied] = ring_[first_];
      first_ = (first_ + 1) % ring_.size();
      --pending_;
    }
    return copied;
  }

 private:
  void convert(const SDL_Event& event) {
    Event converted;
    switch (event.type) {
      case SDL_KEYDOWN:
      case SDL_KEYUP: {
        if (event.type == SDL_KEYDOWN && event.key.repeat) return;
        const char* name = SDL_GetKeyName(event.key.keysym.sym);
        if (name == nullptr || name[0] == '\0') name = SDL_GetScancodeName(event.key.keysym.scancode);
        if (name == nullptr || name[0] == '\0') return;
        if (event.type == SDL_KEYDOWN && event.key.keysym.sym == SDLK_F11) toggle_fullscreen();
        converted.type = event.type == SDL_KEYDOWN ? EventType::key_press : EventType::key_release;
        copy_key_name(name, converted.key);
        break;
      }
      case SDL_WINDOWEVENT:
        if (event.window.windowID != window_id_) return;
        if (event.window.event == SDL_WINDOWEVENT_SIZE_CHANGED || event.window.event == SDL_WINDOWEVENT_RESIZED) {
          converted.type = EventType::resized;
          converted.size = size();
        } else if (event.window.event == SDL_WINDOWEVENT_CLOSE) {
          converted.type = EventType::close_requested;
          closed_ = true;
        } else {
          return;
        }
        break;
      case SDL_QUIT:
        converted.type = EventType::close_requested;
        closed_ = true;
        break;
      default:
        return;
    }
    // SDL reports one resize as RESIZED and SIZE_CHANGED, and one close as a window close and
    // SDL_QUIT: the player hears each once.
    if (pending_ > 0 && converted.type != EventType::key_press && converted.type != EventType::key_release) {
      const Event& last = ring_[(first_ + pending_ - 1) % ring_.size()];
      if (last.type == converted.type && last.size == converted.size) return;
    }
    ring_[(first_ + pending_) % ring_.size()] = converted;
    ++pending_;
  }

  void toggle_fullscreen() {
    const bool fullscreen = (SDL_GetWindowFlags(window_) & SDL_WINDOW_FULLSCREEN_DESKTOP) != 0;
    SDL_SetWindowFullscreen(window_, fullscreen ? 0 : SDL_WINDOW_FULLSCREEN_DESKTOP);
  }

  SDL_Window* window_;
  SDL_GLContext context_;
  bool srgb_, vsync_;
  Uint32 window_id_;
  int event_fd_ = -1;
  bool closed_ = false;
  // Converted events the caller had no room for, oldest at first_; SDL's own queue holds the rest.
  std::array<Event, 32> ring_{};
  std::size_t first_ = 0, pending_ = 0;
};

// What SDL_CreateWindow and SDL_GL_CreateContext need, set again before each attempt.
void set_gl_attributes(bool srgb, bool debug) {
  SDL_GL_ResetAttributes();
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_ES);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 3);
  SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 1);
  if (debug) SDL_GL_SetAttribute(SDL_GL_CONTEXT_FLAGS, SDL_GL_CONTEXT_DEBUG_FLAG);
  SDL_GL_SetAttribute(SDL_GL_RED_SIZE, 8);
  SDL_GL_SetAttribute(SDL_GL_GREEN_SIZE, 8);
  SDL_GL_SetAttribute(SDL_GL_BLUE_SIZE, 8);
  // The renderer draws depth into its own targets; the window only receives the present pass.
  SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 0);
  SDL_GL_SetAttribute(SDL_GL_STENCIL_SIZE, 0);
  SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
  SDL_GL_SetAttribute(SDL_GL_FRAMEBUFFER_SRGB_CAPABLE, srgb ? 1 : 0);
}

}  // namespace

std::unique_ptr<Platform> create_window(const Options& options, std::string& error) {
  // SDL_VIDEODRIVER picks a driver by hand (say for SDL's offscreen driver); otherwise a display is needed.
  if (!std::getenv("SDL_VIDEODRIVER") && !std::getenv("DISPLAY") && !std::getenv("WAYLAND_DISPLAY")) {
    error =
        "window: no display (DISPLAY is not set; the window platform needs X11 or Wayland, use --platform egl "
        "for headless)";
    return nullptr;
  }
  // GLX would give desktop GL; EGL gives Mesa's OpenGL ES 3.1 on X11 as on Wayland.
  SDL_SetHint(SDL_HINT_VIDEO_X11_FORCE_EGL, "1");
  // SIGINT and SIGTERM stay the player's own (SDL would turn them into SDL_QUIT).
  SDL_SetHint(SDL_HINT_NO_SIGNAL_HANDLERS, "1");
  if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0) {
    error = std::string("window: SDL could not open the display (") + SDL_GetError() + ")";
    return nullptr;
  }
  Uint32 flags = SDL_WINDOW_OPENGL | SDL_WINDOW_RESIZABLE | SDL_WINDOW_ALLOW_HIGHDPI;
  if (options.fullscreen) flags |= SDL_WINDOW_FULLSCREEN_DESKTOP;
  // The sRGB request fails window creation where EGL lacks EGL_KHR_gl_colorspace; then the
  // window is made without it and the present pass encodes in the shader.
  SDL_Window* window = nullptr;
  for (bool srgb : {true, false}) {
    set_gl_attributes(srgb, options.debug_context);
    window = SDL_CreateWindow("ssao-player", SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED, options.size.width,
                              options.size.height, flags);
    if (window) break;
  }
  if (!window) {
    error = std::string("window: SDL could not make a window with an OpenGL ES 3.1 framebuffer (") + SDL_GetError() + ")";
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
    return nullptr;
  }
  SDL_GLContext context = SDL_GL_CreateContext(window);
  if (!context) {
    error = std::string("window: SDL could not make an OpenGL ES 3.1 context (") + SDL_GetError() + ")";
    SDL_DestroyWindow(window);
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
    return nullptr;
  }
  // Vsync where the swap chain offers it; a window without it still works, only faster than the display.
  const bool vsync = SDL_GL_SetSwapInterval(1) == 0;
  SDL_StopTextInput();  // keys arrive as key events; no input method composing text
  return std::make_unique<WindowPlatform>(window, context, query_srgb_back_buffer(), vsync);
}

}  // namespace platform
