// A Looking Glass calibration (visual.json, lightfield::parse_calibration), as the vendor's tools
// write it onto the device. Refusal is a false return; anything thrown, or any sanitizer report, is a
// finding. An accepted calibration's interleave is evaluated at the panel's corners.
#include <cstddef>
#include <cstdint>
#include <string>

#include "lightfield/display_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  lightfield::Calibration calibration;
  std::string error;
  if (lightfield::parse_calibration(std::string_view(reinterpret_cast<const char*>(data), size), "visual.json", calibration,
                                    error)) {
    const lightfield::Interleave interleave = lightfield::interleave_of(calibration, 45);
    for (int channel = 0; channel < 3; ++channel) {
      (void)lightfield::view_of_subpixel(interleave, calibration, 0, 0, channel);
      (void)lightfield::view_of_subpixel(interleave, calibration, calibration.screen_width - 1, calibration.screen_height - 1,
                                         channel);
    }
  }
  return 0;
}
