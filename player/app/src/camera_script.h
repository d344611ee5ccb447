#pragma once
// The mock camera's script (`player play --camera-script`): `t_ms unplug|replug` a line (whole
// milliseconds), '#' comments, times not decreasing; what a test does to the mock camera. Header-only and free of the
// app's GL dependencies so tests/fuzz (camera_script) can feed it text.
#include "base/parse.h"

#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace app {

struct CameraStep {
  double at_s;
  bool plugged;
};

// Times beyond this (a hundred years) are typos, as in button scripts.
inline constexpr long long kMaxCameraScriptMs = 100LL * 365 * 24 * 3600 * 1000;

// `source` names the file in messages. Every line is blank, a comment, or a step: a line of anything
// else (random bytes, a time of `nan`) is an error, as in button scripts. Returns false with
// "<source>:<line>: <field>: expected ..., got ..." in `error`.
inline bool parse_camera_script_text(std::string_view text, const std::string& source, std::vector<CameraStep>& out,
                                     std::string& error) {
  std::istringstream in{std::string(text)};
  std::string line;
  long long last_ms = 0;
  for (int number = 1; std::getline(in, line); ++number) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    std::string time, what, extra;
    if (!(words >> time)) continue;  // blank or comment
    const std::string where = source + ":" + std::to_string(number) + ": ";
    long long ms = 0;
    if (!base::parse_int(time, 0, kMaxCameraScriptMs, ms)) {
      error = where + "time: expected milliseconds from 0 to " + std::to_string(kMaxCameraScriptMs) + " (100 years), got '" +
              time + "'";
      return false;
    }
    if (ms < last_ms) {
      error = where + "time: expected times that do not decrease, got " + time + " after " + std::to_string(last_ms);
      return false;
    }
    if (!(words >> what) || (what != "unplug" && what != "replug")) {
      error = where + "action: expected 'unplug' or 'replug', got '" + what + "'";
      return false;
    }
    if (words >> extra) {
      error = where + "expected 2 fields, got more: '" + extra + "'";
      return false;
    }
    last_ms = ms;
    out.push_back({static_cast<double>(ms) / 1000.0, what == "replug"});
  }
  return true;
}

}  // namespace app
