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
  double duration_s = 10.0;         // scenes named on the command line: seconds each
  double period_s = 20.0;           // ... on a turntable of this many seconds per turn
  std::string platform = "auto";
  int width = 1024, height = 768;
  bool fullscreen = false;
  std::string overlay = "auto";     // the LED and state panel: on, off, or auto (on in a window)
  long long frames = 0;             // stop after this many frames; 0: run until stopped
  std::string out_dir;              // headless: write every frame as DIR/frame-NNNNNN.png
  double fps = 0.0;                 // pace frames and the playlist clock; 0: as fast as possible, 1/30 s a frame
  std::string board_file;
  std::string hal;                  // "linux", "mock" or empty (linux with a board file, else mock)
  std::string buttons_script;       // mock buttons: `t_ms BUTTON press|release` lines
  std::string status_file;          // overrides the board's
  std::string log_file;             // a line per frame: frame, item, state, leds, actions, times, memory (tests, benchmarks)
  std::string camera_script;        // mock camera: `t_ms unplug|replug` lines (tests)
  render::FrameSettings settings;   // the command line's settings; a playlist item's `ao` overrides them
};

// Returns 0 after a clean stop (SIGTERM, SIGINT, --frames, the end of a playlist without loop),
// 1 for bad input found before the first frame, 2 when the platform could not be made.
int run_play(const PlayOptions& options, std::ostream& out, std::ostream& err);

}  // namespace app
