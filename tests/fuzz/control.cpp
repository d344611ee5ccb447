// The control socket's messages (control::parse_command): whatever a local client, or the fleet
// agent on a broker's behalf, sends. A refusal says why; what is accepted formats back to itself.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "control/control.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string message(reinterpret_cast<const char*>(data), size);
  control::Command command;
  std::string error;
  if (!control::parse_command(message, command, error)) {
    if (error.empty()) std::abort();
    return 0;
  }
  control::Command again;
  if (!control::parse_command(control::format_command(command), again, error) || again.verb != command.verb ||
      again.item != command.item || again.display_on != command.display_on)
    std::abort();
  return 0;
}
