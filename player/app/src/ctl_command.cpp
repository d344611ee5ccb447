#include "app/ctl_command.h"

#include "control/control.h"

#include <cmath>
#include <ostream>

namespace app {

int run_ctl(const CtlOptions& options, std::ostream& out, std::ostream& err) {
  std::string message;
  for (const std::string& word : options.words) message += (message.empty() ? "" : " ") + word;
  // Checked here too, so a typo is told at once and never reaches the player.
  control::Command command;
  std::string error;
  if (!control::parse_command(message, command, error)) {
    err << "error: " << error << "\n";
    return 2;
  }
  if (!(options.timeout_s > 0.0) || options.timeout_s > 3600.0) {
    err << "error: --timeout: expected seconds in (0, 3600], got " << options.timeout_s << "\n";
    return 2;
  }
  std::string reply;
  if (!control::send_command(options.control, control::format_command(command),
                             static_cast<int>(std::ceil(options.timeout_s * 1000.0)), reply, error)) {
    err << "error: " << error << "\n";
    return 2;
  }
  if (control::reply_ok(reply)) {
    out << reply << "\n";
    return 0;
  }
  err << reply << "\n";
  return 1;
}

}  // namespace app
