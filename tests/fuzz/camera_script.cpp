// The mock camera's script (`player play --camera-script`, app::parse_camera_script_text). Besides
// never crashing: an accepted script's steps have finite times that never decrease, as the play
// loop's "next step due" check assumes.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "camera_script.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<app::CameraStep> steps;
  std::string error;
  if (!app::parse_camera_script_text(std::string_view(reinterpret_cast<const char*>(data), size), "camera.script", steps, error))
    return 0;
  double last = 0;
  for (const app::CameraStep& step : steps) {
    if (!std::isfinite(step.at_s) || step.at_s < last) __builtin_trap();
    last = step.at_s;
  }
  return 0;
}
