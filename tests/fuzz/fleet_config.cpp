// The fleet agent's configuration (fleet::parse_config): TOML an installer writes onto every board.
// Refusal is a false return with a message naming the file; a throw escaping, a crash or a
// sanitizer report is a finding. What it accepts must make sense to the agent.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "fleet/fleet.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fleet::Config config;
  std::string error;
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (fleet::parse_config(text, "fleet.toml", "0123456789abcdef", config, error)) {
    // Accepted: a broker to reach, topics without wildcards, periods the loop can keep.
    if (config.host.empty() || config.port < 1 || config.port > 65535 || config.client_id.empty() ||
        !(config.status_period_s >= 0.2) || config.keepalive_s < 5)
      std::abort();
    for (const std::string& topic : fleet::command_subscriptions(config))
      if (topic.find('#') != std::string::npos) std::abort();
    (void)fleet::discovery_messages(config, "fuzz");
  } else if (error.rfind("fleet.toml:", 0) != 0) {
    std::abort();  // every refusal names the file
  }
  return 0;
}
