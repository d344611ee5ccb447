#pragma once
// `player play`: the kiosk. Plays a playlist (or scenes on a turntable) until stopped, answers the
// buttons, drives the status LEDs and file, watches the content for changes and checks the display
// with the camera. `player render` is a one-item run of the same path.
#include "render/settings.h"

#include <iosfwd>
#include <string>
#include <vector>

namespace app {

struct PlayOptions {
  std::vector<std::string> inputs;  // one .toml playlist, or scene files / builtin:NAME; empty: builtin:demo
  std::string content_root;         // paths of a playlist must stay inside; default the playlist's folder
  std::string environment;          // --environment: what lights items that name none (empty: the studio)
  double duration_s = 10.0;         // scenes named on the command line: seconds each
  double period_s = 20.0;           // ... on a turntable of this many seconds per turn
  std::string platform = "auto";    // auto: kms without a display server, window with one, egl otherwise
  int width = 1024, height = 768;
  // kms: device, connector, mode and atomic modesetting (platform::Options), and the file to write
  // what the display shows at exit, captured through the DRM writeback connector (tests, diagnosis).
  std::string drm_device, drm_connector = "auto", drm_mode = "preferred", drm_atomic = "auto", drm_writeback;
  std::string snapshot;  // with --frames N: frame N-1 as drawn onto the surface (PNG), before it is presented
  int rotation = -1;     // 0, 90, 180, 270 clockwise; -1: the board file's [display] rotation
  bool fullscreen = false;
  std::string overlay = "auto";  // the LED and state panel: on, off, or auto (on in a window)
  long long frames = 0;          // stop after this many frames; 0: run until stopped
  std::string out_dir;           // headless: write every frame as DIR/frame-NNNNNN.png
  double fps = 0.0;              // pace frames and the playlist clock; 0: as fast as possible, 1/30 s a frame
  std::string board_file;
  std::string hal;             // "linux", "mock" or empty (linux with a board file, else mock)
  std::string buttons_script;  // mock buttons: `t_ms BUTTON press|release` lines
  std::string status_file;     // overrides the board's
  std::string control;         // --control: the control socket's path, overriding the board's; "off": none
  std::string metrics_file;    // --metrics: Prometheus textfile-collector file, overriding the board's
  std::string log_file;        // a line per frame: frame, item, state, leds, actions, times, memory (tests, benchmarks)
  std::string camera_script;   // mock camera: `t_ms unplug|replug` lines (tests)
  std::string shader_cache;    // --shader-cache: a folder, "off", or empty for the default (app/src/shader_cache.h)
  // --start-time: the wall-clock time (Unix seconds) the run starts at, for previews and tests of
  // opening hours and wallclock playlists; negative: now.
  double start_time_s = -1.0;
  render::FrameSettings settings;  // the command line's settings; a playlist item's `ao` overrides them
};

// --start-time's value: RFC 3339 ("2026-12-07T17:59:30Z", "2026-12-07T18:59:30+01:00") or Unix
// seconds, as Unix seconds. False with what was expected.
bool parse_start_time(const std::string& text, double& unix_s, std::string& error);

// Returns 0 after a clean stop (SIGTERM, SIGINT, --frames, the end of a playlist without loop),
// 1 for bad input found before the first frame (or a --drm-writeback capture that failed), 2 when the platform could not be made,
// 3 when the display stopped taking frames (kms: page flips that never complete), so a service manager restarts it.
int run_play(const PlayOptions& options, std::ostream& out, std::ostream& err);

}  // namespace app
