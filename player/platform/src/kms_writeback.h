#pragma once
// Reading back what the display shows through a writeback connector (vkms has one; so do many
// embedded display controllers): an atomic commit attaches the connector with a dumb buffer to the
// CRTC, the out-fence says when the frame is written, and the buffer is mapped and converted.
#include <cstdint>
#include <string>
#include <vector>

namespace platform::kms {

struct WritebackCapture {
  int fd = -1;
  std::uint32_t writeback = 0;  // the writeback connector
  std::uint32_t crtc = 0;       // the CRTC scanning out the display
  // The display's connector and its CRTC_ID property: detached for the capture where the driver
  // cannot clone, attached again after.
  std::uint32_t display_connector = 0, display_connector_crtc = 0;
  std::string display_name;   // "HDMI-A-1", for errors
  int width = 0, height = 0;  // the mode's
  int timeout_ms = 0;         // for the commit attaching the writeback and its out-fence; again for detaching it
};

// Top-down RGBA8 of what the CRTC composes. False and why otherwise. `needs_modeset`: the commit
// that detached the writeback again was refused, so the next frame must set the mode.
bool capture_writeback(const WritebackCapture& capture, std::vector<std::uint8_t>& rgba, std::string& error, bool& needs_modeset);

}  // namespace platform::kms
