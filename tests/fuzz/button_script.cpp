// Mock button scripts (hal::parse_button_script): `player play --buttons-script` and the board
// file's mock.button_script. ConfigError is the only way to refuse.
#include <cstddef>
#include <cstdint>
#include <string>

#include "hal/board.h"  // ConfigError
#include "hal/mock.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    (void)hal::parse_button_script(std::string(reinterpret_cast<const char*>(data), size), "buttons.script");
  } catch (const hal::ConfigError&) {
  }
  return 0;
}
