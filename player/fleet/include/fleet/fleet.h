#pragma once
// `player fleet`: the one program of the player that talks to the network. It carries a player's
// state to an MQTT broker (and announces it to Home Assistant) and the broker's commands to the
// player, through the player's status file and control socket only, so the player itself stays
// offline (PrivateNetwork=yes) and never waits on a broker. docs/fleet.md has the topics.
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

namespace fleet {

inline constexpr std::string_view kDefaultConfig = "/etc/ssao-player/fleet.toml";

struct Config {
  std::string source;     // the file it was read from, for messages
  bool tls = false;       // mqtts://
  std::string host;       // the broker
  int port = 1883;        // 1883, or 8883 with TLS, unless the URL names one
  std::string client_id;  // default: the machine id
  std::string prefix = "ssao-player";
  std::string username;       // empty: none
  std::string password_file;  // read at start; empty: none
  std::string ca_file;        // empty with TLS: the system's certificates
  bool insecure = false;      // TLS without checking the broker's certificate (written out, never a default)
  std::string status_file = "/run/ssao-player/status.json";
  std::string control = "/run/ssao-player/control";
  double status_period_s = 5.0;
  int keepalive_s = 30;
  double reconnect_max_s = 60.0;                   // the backoff's ceiling
  std::string discovery_prefix = "homeassistant";  // empty: no Home Assistant discovery
  std::string name;                                // the device's name in Home Assistant (default: the client id)
  int screenshot_max_kb = 256;                     // a screenshot's JPEG is scaled down until it fits
};

// The file's text as a configuration. `machine_id` stands in for client_id when the file has none
// (empty: client_id is required). False and why, naming file, line and key.
bool parse_config(std::string_view text, const std::string& source, const std::string& machine_id, Config& config,
                  std::string& error);
// The file at `path`, with /etc/machine-id as the default client id.
bool load_config(const std::string& path, Config& config, std::string& error);

// A message to publish: topic, payload, retained or not.
struct Message {
  std::string topic, payload;
  bool retain = true;
};

// The topics of one player.
std::string state_topic(const Config& config);
std::string availability_topic(const Config& config);
std::string reply_topic(const Config& config);
std::string screenshot_topic(const Config& config);  // the presented frame
std::string camera_topic(const Config& config);      // what the check camera sees of the screen
// What a player subscribes to: its own commands and everyone's.
std::vector<std::string> command_subscriptions(const Config& config);
// `topic` a command topic of this player (PREFIX/ID/cmd/VERB or PREFIX/all/cmd/VERB) and the
// payload its arguments: the control socket's message ("item 2"). False and why otherwise.
bool command_of(const Config& config, std::string_view topic, std::string_view payload, std::string& message, std::string& error);

// Home Assistant's MQTT discovery: one device per player with its sensors, binary sensors, buttons
// and camera, each retained. `version`: the player's, for the device's sw_version.
std::vector<Message> discovery_messages(const Config& config, const std::string& version);
// The same topics with empty retained payloads, which make Home Assistant forget the device.
std::vector<Message> discovery_removal(const Config& config);

struct Options {
  std::string config = std::string(kDefaultConfig);
  bool check = false;       // read the configuration, its password and CA files, say what it would do, and exit
  bool remove = false;      // withdraw the player from the broker (discovery, state, availability) and exit
  double duration_s = 0.0;  // stop after this long (0: until SIGTERM or SIGINT), for tests and benchmarks
};

// Runs the agent until SIGTERM/SIGINT: 0 after a clean stop, 2 for a bad configuration.
int run_fleet(const Options& options, const std::string& version, std::ostream& out, std::ostream& err);

}  // namespace fleet
