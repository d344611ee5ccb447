#pragma once
// The mock camera's script (`player play --camera-script`): `t_ms unplug|replug` a line, '#'
// comments, times not decreasing; what a test does to the mock camera. Header-only and free of the
// app's GL dependencies so tests/fuzz (camera_script) can feed it text.
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace app {

struct CameraStep {
  double at_s;
  bool plugged;
};

// `source` names the file in messages. Returns false with "<source>:<line>: expected ..." in `error`.
inline bool parse_camera_script_text(std::string_view text, const std::string& source, std::vector<CameraStep>& out,
                                     std::string& error) {
  std::istringstream in{std::string(text)};
  std::string line;
  double last = 0.0;
  for (int number = 1; std::getline(in, line); ++number) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    double ms = 0.0;
    std::string what;
    if (!(words >> ms)) continue;  // blank or comment
    if (!(words >> what) || (what != "unplug" && what != "replug") || ms < last) {
      error = source + ":" + std::to_string(number) + ": expected `t_ms unplug|replug` with times not decreasing";
      return false;
    }
    last = ms;
    out.push_back({ms / 1000.0, what == "replug"});
  }
  return true;
}

}  // namespace app
