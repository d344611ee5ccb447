// The desktop window platform, run under Xvfb (ctest's gl.window_under_xvfb): it renders the same
// frame as headless EGL, drains events without blocking and answers a resize with a `resized` event.
// The Window* tests need a display; gl_tests' discovered entries leave them out.
#include "harness.h"

#include <OpenImageIO/imageio.h>
#include <SDL.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <thread>

namespace {

using test::Harness;

// Both platforms run the same shaders on the same driver (Mesa's llvmpipe under Xvfb), so the frame
// is the same up to the last step: the window's framebuffer may lack sRGB where the EGL pbuffer has
// it (or the other way round), and then one side encodes linear colour in the shader and the other
// in the framebuffer. Each rounds to 8 bits its own way, so a channel may differ by 1/255, in any
// share of the pixels. Where both encode the same way nothing may differ.
constexpr int kMaxChannelDifference = 1;

render::FrameSettings settings_for(int width, int height) {
  render::FrameSettings settings;
  settings.width = width;
  settings.height = height;
  settings.check_errors = true;
  return settings;
}

bool has_display() {
  return std::getenv("DISPLAY") != nullptr || std::getenv("WAYLAND_DISPLAY") != nullptr;
}

#define SKIP_WITHOUT_DISPLAY() \
  if (!has_display()) GTEST_SKIP() << "no DISPLAY: ctest runs the Window tests under xvfb-run (gl.window_under_xvfb)"

void write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba) {
  auto output = OIIO::ImageOutput::create(path);
  if (output && output->open(path, OIIO::ImageSpec(width, height, 4, OIIO::TypeDesc::UINT8))) {
    output->write_image(OIIO::TypeDesc::UINT8, rgba.data());
    output->close();
  }
}

// Drains up to `rounds` times, a few milliseconds apart, until `wanted` accepts an event.
template <typename Wanted>
bool drain_until(platform::Platform& platform, int rounds, Wanted wanted) {
  platform::Event events[8];
  for (int round = 0; round < rounds; ++round) {
    const std::size_t count = platform.drain_events(events);
    for (std::size_t i = 0; i < count; ++i)
      if (wanted(events[i])) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

TEST(Window, RendersTheFrameHeadlessEglRenders) {
  SKIP_WITHOUT_DISPLAY();
  const render::FrameSettings settings = settings_for(160, 120);
  // One context at a time on this thread: the window's frame is read and the window closed before
  // the EGL context is made.
  std::vector<uint8_t> shown;
  bool window_srgb = false;
  std::string window_renderer;
  {
    Harness window;
    ASSERT_TRUE(window.start("window", "builtin:demo", settings));
    ASSERT_EQ(window.platform->size(), (platform::Size{160, 120}));
    ASSERT_EQ(window.platform->framebuffer(), 0u);
    // Read before present(): after a swap the back buffer's contents are undefined.
    shown = render::read_presented(window.target(), settings.width, settings.height);
    EXPECT_EQ(window.renderer.gl_error(), "");
    EXPECT_TRUE(window.platform->present());
    window_srgb = window.platform->srgb_framebuffer();
    window_renderer = window.caps.renderer;
    std::cout << "window: " << window.platform->description() << "; " << window_renderer << "\n";
  }
  Harness egl;
  ASSERT_TRUE(egl.start("egl", "builtin:demo", settings));
  const std::vector<uint8_t> expected = render::read_presented(egl.target(), settings.width, settings.height);
  std::cout << "egl: " << egl.platform->description() << "; " << egl.caps.renderer << "\n";
  if (egl.caps.renderer != window_renderer)
    GTEST_SKIP() << "the window runs on " << window_renderer << " and headless EGL on " << egl.caps.renderer
                 << ": frames from two drivers are not compared";
  ASSERT_EQ(shown.size(), expected.size());

  std::vector<uint8_t> diff(shown.size(), 255);
  size_t differing = 0;
  int worst = 0;
  for (size_t p = 0; p < shown.size(); p += 4) {
    int pixel_worst = 0;
    for (size_t c = 0; c < 4; ++c) pixel_worst = std::max(pixel_worst, std::abs(int(shown[p + c]) - int(expected[p + c])));
    worst = std::max(worst, pixel_worst);
    differing += pixel_worst > 0 ? 1 : 0;
    diff[p] = static_cast<uint8_t>(std::min(255, pixel_worst * 64));
    diff[p + 1] = diff[p + 2] = 0;
  }
  const bool same_encoding = window_srgb == egl.platform->srgb_framebuffer();
  const size_t pixels = shown.size() / 4;
  std::cout << "window sRGB framebuffer: " << window_srgb << ", egl: " << egl.platform->srgb_framebuffer() << "; max difference "
            << worst << "/255 in " << differing << " of " << pixels << " pixels\n";
  const int allowed = same_encoding ? 0 : kMaxChannelDifference;
  if (worst > allowed) {
    const std::string base = std::string(PLAYER_TEST_OUTPUT_DIR) + "/window_demo";
    write_png(base + ".actual.png", settings.width, settings.height, shown);
    write_png(base + ".expected.png", settings.width, settings.height, expected);
    write_png(base + ".diff.png", settings.width, settings.height, diff);
    ADD_FAILURE() << "the window's frame differs from headless EGL's by up to " << worst << "/255 (allowed " << allowed << ") in "
                  << differing << " of " << pixels << " pixels; see " << base << ".actual.png, .expected.png and .diff.png";
  }
}

TEST(Window, EventsDrainWithoutBlocking) {
  SKIP_WITHOUT_DISPLAY();
  Harness h;
  std::string error;
  ASSERT_TRUE(h.open("window", settings_for(160, 120), error)) << error;
  platform::Event events[4];
  // Whatever the window system sent at creation (focus, exposure) is converted or dropped; after that
  // an idle window has nothing, and asking must return at once, again and again.
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < 100; ++i) (void)h.platform->drain_events(events);
  EXPECT_EQ(h.platform->drain_events(events), 0u);
  // Generous: a blocking drain would wait for input that never comes under Xvfb, far longer than this.
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
  EXPECT_EQ(h.platform->drain_events({}), 0u);
  EXPECT_TRUE(h.platform->present());
}

// Keys reach a board file's button mapping by the names the board file writes for them: SDL's name
// in lower case with '-' for a space ("left-shift", "keypad-1"), the names the evdev keyboards give
// the same keys on a board (hal's board_key_name), so one board file works on both. A held key's
// auto-repeat is not a press; its release is a key_release.
TEST(Window, KeysArriveByTheNamesBoardFilesGiveThem) {
  SKIP_WITHOUT_DISPLAY();
  Harness h;
  std::string error;
  ASSERT_TRUE(h.open("window", settings_for(160, 120), error)) << error;
  platform::Event events[8];
  while (h.platform->drain_events(events) > 0) {
  }
  auto send = [](Uint32 type, SDL_Keycode key, bool repeat) {
    SDL_Event event{};
    event.type = type;
    event.key.type = type;
    event.key.state = type == SDL_KEYDOWN ? SDL_PRESSED : SDL_RELEASED;
    event.key.repeat = repeat ? 1 : 0;
    event.key.keysym.sym = key;
    event.key.keysym.scancode = SDL_GetScancodeFromKey(key);
    return SDL_PushEvent(&event) == 1;
  };
  auto received = [&](platform::EventType type) {
    std::vector<std::string> keys;
    for (int round = 0; round < 20; ++round) {
      const std::size_t count = h.platform->drain_events(events);
      for (std::size_t i = 0; i < count; ++i)
        if (events[i].type == type) keys.emplace_back(events[i].key);
      if (!keys.empty() && count == 0) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return keys;
  };
  const std::pair<SDL_Keycode, const char*> keys[] = {
      {SDLK_SPACE, "space"},   {SDLK_LSHIFT, "left-shift"}, {SDLK_RCTRL, "right-ctrl"},
      {SDLK_KP_1, "keypad-1"}, {SDLK_RETURN, "return"},     {SDLK_n, "n"},
      {SDLK_F5, "f5"},         {SDLK_PAGEDOWN, "pagedown"}};
  for (const auto& [key, name] : keys) {
    SCOPED_TRACE(name);
    ASSERT_TRUE(send(SDL_KEYDOWN, key, false)) << SDL_GetError();
    ASSERT_TRUE(send(SDL_KEYDOWN, key, true)) << SDL_GetError();  // auto-repeat while held
    EXPECT_EQ(received(platform::EventType::key_press), std::vector<std::string>{name});
    ASSERT_TRUE(send(SDL_KEYUP, key, false)) << SDL_GetError();
    EXPECT_EQ(received(platform::EventType::key_release), std::vector<std::string>{name});
  }
}

TEST(Window, AResizeRequestArrivesAsAResizedEvent) {
  SKIP_WITHOUT_DISPLAY();
  Harness h;
  ASSERT_TRUE(h.start("window", "builtin:demo", settings_for(160, 120)));
  platform::Event events[8];
  while (h.platform->drain_events(events) > 0) {
  }
  // Xvfb has no window manager, so the server applies the size as asked.
  const platform::Size wanted{200, 150};
  std::string error;
  ASSERT_TRUE(h.platform->resize(wanted, error)) << error;
  // No room: whatever arrives stays queued for the next call.
  for (int i = 0; i < 5; ++i) EXPECT_EQ(h.platform->drain_events({}), 0u);
  EXPECT_TRUE(drain_until(*h.platform, 200, [&](const platform::Event& event) {
    return event.type == platform::EventType::resized && event.size == wanted;
  })) << "no resized event for 200x150";
  EXPECT_EQ(h.platform->size(), wanted);
  // The new size draws: a frame at 200x150 renders into the window without GL errors.
  const render::FrameSettings settings = settings_for(wanted.width, wanted.height);
  ASSERT_TRUE(h.renderer.configure(settings, error)) << error;
  h.renderer.render(scene::frame(h.scene.bounds, {}, wanted.width, wanted.height));
  const std::vector<uint8_t> frame = render::read_presented(h.target(), wanted.width, wanted.height);
  EXPECT_EQ(h.renderer.gl_error(), "");
  size_t lit = 0;
  for (size_t p = 0; p < frame.size(); p += 4) lit += frame[p + 1] > 8 ? 1 : 0;
  EXPECT_GT(lit, frame.size() / 4 / 10) << "the demo covers part of the resized window";
  EXPECT_TRUE(h.platform->present());
}

TEST(Window, PresentSucceedsFrameAfterFrameWhileTheWindowIsOpen) {
  SKIP_WITHOUT_DISPLAY();
  Harness h;
  ASSERT_TRUE(h.start("window", "builtin:demo", settings_for(160, 120)));
  platform::Event events[8];
  for (int frame = 0; frame < 10; ++frame) {
    (void)h.platform->drain_events(events);
    h.renderer.render(h.camera);
    ASSERT_TRUE(h.platform->present()) << "frame " << frame;
  }
  EXPECT_EQ(h.renderer.gl_error(), "");
  EXPECT_GE(h.platform->event_fd(), 0) << "an X11 window has the connection's fd";
}

// Runs everywhere (not a Window* test): without a display the platform says so, without crashing.
std::vector<uint8_t> read_png(const std::string& path, int& width, int& height) {
  auto input = OIIO::ImageInput::open(path);
  if (!input) return {};
  const OIIO::ImageSpec& spec = input->spec();
  width = spec.width;
  height = spec.height;
  std::vector<uint8_t> pixels(static_cast<size_t>(width) * static_cast<size_t>(height) * 4);
  input->read_image(0, 0, 0, 4, OIIO::TypeDesc::UINT8, pixels.data());
  return pixels;
}

// `player play` in a window draws the LED and state panel in the top-left corner, and nothing else
// differs from the headless frame: the panel region changes, the rest matches within the 1/255 of
// an sRGB encode done elsewhere (see RendersTheFrameHeadlessEglRenders).
TEST(WindowOverlay, PlayShowsTheLedPanelInTheCornerOnly) {
  SKIP_WITHOUT_DISPLAY();
  const std::string dir = std::string(PLAYER_TEST_OUTPUT_DIR) + "/window-overlay";
  // A still camera: the window runs on the real clock, the headless run on its own. Scenes load off
  // the frame loop, so the two may show it from different frames on: without temporal accumulation
  // the AO of the last frame does not depend on how many came before. The window is paced, so the
  // load (with the studio environment's prefiltering, about 0.2 s) ends well inside its second.
  const std::string common =
      " play " + dir + "/still.toml --size 320x240 --frames 30 --fps 30 --temporal off --status " + dir + "/status.json";
  ASSERT_EQ(std::system(("rm -rf " + dir + " && mkdir -p " + dir).c_str()), 0);
  {
    std::ofstream playlist(dir + "/still.toml");
    playlist << "[[item]]\nscene = \"builtin:demo\"\ncamera = { motion = \"still\" }\n";
  }
  ASSERT_EQ(
      std::system((std::string(PLAYER_BINARY) + common + " --platform window --out " + dir + "/window > /dev/null").c_str()), 0);
  ASSERT_EQ(std::system((std::string(PLAYER_BINARY) + common + " --platform egl --out " + dir + "/egl > /dev/null").c_str()), 0);
  int w = 0, h = 0, ew = 0, eh = 0;
  const auto window = read_png(dir + "/window/frame-000029.png", w, h);
  const auto egl = read_png(dir + "/egl/frame-000029.png", ew, eh);
  ASSERT_FALSE(window.empty());
  ASSERT_EQ(window.size(), egl.size());
  // The panel: two lamps and the state line, 6 px from the top-left corner (overlay.cpp).
  size_t panel_changed = 0, outside_off = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = (static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 4;
      int difference = 0;
      for (int c = 0; c < 3; ++c) difference = std::max(difference, std::abs(window[i + c] - egl[i + c]));
      const bool in_panel = x >= 6 && x < 200 && y >= 6 && y < 6 + 2 * 6 + 3 * 20;
      const bool near_panel = x < 260 && y < 100;  // its exact width follows the longest line
      if (in_panel)
        panel_changed += difference > 8 ? 1 : 0;
      else if (!near_panel && difference > 1)
        ++outside_off;
    }
  EXPECT_GT(panel_changed, 194u * 84u / 2) << "the panel is not there";
  EXPECT_EQ(outside_off, 0u);
}

TEST(NoDisplay, TheWindowPlatformSaysWhyInOneLine) {
  std::vector<std::pair<const char*, std::string>> saved;
  for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY", "SDL_VIDEODRIVER"}) {
    if (const char* value = std::getenv(name)) saved.emplace_back(name, value);
    unsetenv(name);
  }
  platform::Options options;
  options.name = "window";
  options.size = {64, 64};
  std::string error;
  const auto session = gl::Session::open(options, error);
  for (const auto& [name, value] : saved) setenv(name, value.c_str(), 1);
  EXPECT_EQ(session, nullptr);
  EXPECT_EQ(error,
            "window: no display (DISPLAY is not set; the window platform needs X11 or Wayland, use --platform egl for "
            "headless)");
}

}  // namespace
