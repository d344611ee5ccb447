// Light field display files (lightfield::parse_display): TOML an installer copies next to the content.
// A quilt names its calibration relative to the file, so a valid visual.json waits in the scratch
// folder and the whole quilt path runs. Refusal is a false return; anything thrown, or any sanitizer
// report, is a finding.
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "fuzz_dir.h"
#include "lightfield/display_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string source = [] {
    std::ofstream(fuzz::scratch_dir() / "visual.json")
        << R"({"pitch": {"value": 52.58}, "slope": {"value": -7.22}, "center": {"value": 0.56}, "DPI": {"value": 324},
               "screenW": {"value": 1536}, "screenH": {"value": 2048}, "invView": {"value": 1}, "viewCone": {"value": 40}})";
    return (fuzz::scratch_dir() / "display.toml").string();
  }();
  lightfield::Display display;
  std::string error;
  if (lightfield::parse_display(std::string(reinterpret_cast<const char*>(data), size), source, display, error) &&
      display.type == lightfield::DisplayType::modules) {
    // What the renderer does next with an accepted file: every module's geometry and visibility.
    for (int k = 0; k < display.views(); ++k) {
      const lightfield::Module module = lightfield::module_of(display.modules, k);
      (void)lightfield::sees(module, display.modules.physical_roi);
      (void)lightfield::physical_to_image(module, {0.0, 0.0, 0.0});
    }
  }
  return 0;
}
