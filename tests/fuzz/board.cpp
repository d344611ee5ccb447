// Board files (hal::parse_board): TOML an installer copies onto the kiosk. A ConfigError is the
// parser's one way to refuse; anything else escaping, or any sanitizer report, is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_dir.h"
#include "hal/board.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // Relative paths in the file (mock.button_script, mock.camera_images) resolve against its folder.
  static const std::string source = (fuzz::scratch_dir() / "board.toml").string();
  try {
    const hal::BoardConfig board = hal::parse_board(std::string(reinterpret_cast<const char*>(data), size), source);
    for (const hal::ButtonConfig& b : board.buttons) (void)b.line.describe();
    for (const hal::LedConfig& l : board.leds) (void)l.line.describe();
  } catch (const hal::ConfigError&) {
  }
  return 0;
}
