#pragma once
// Which connector and mode the kms platform drives, decided on plain data read from the device, so
// the choice (mpv's --drm-connector and --drm-mode rules) is tested without a display.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace platform::kms {

struct Mode {
  int width = 0, height = 0;
  double refresh_hz = 0.0;  // from the pixel clock and totals, not the rounded vrefresh
  bool preferred = false;
  bool interlaced = false;
};

enum class ConnectorState : std::uint8_t { connected, disconnected, unknown };

struct Connector {
  std::uint32_t id = 0;
  std::string name;  // as the kernel names it in sysfs: "HDMI-A-1", "Virtual-1", "DSI-1"
  ConnectorState state = ConnectorState::unknown;
  std::vector<Mode> modes;
};

// --drm-mode: preferred | highest | WxH[@R]
struct ModeRequest {
  enum class Kind : std::uint8_t { preferred, highest, size } kind = Kind::preferred;
  int width = 0, height = 0;
  double refresh_hz = 0.0;  // 0: the highest refresh at that size
};
bool parse_mode_request(std::string_view text, ModeRequest& out, std::string& error);
std::string to_string(const ModeRequest& request);

std::string_view to_string(ConnectorState state);
// "640x480@59.94"
std::string describe(const Mode& mode);

// --drm-connector NAME or "auto" (the first connected one). Returns the index into `connectors`,
// or -1: `waiting` true when the wanted connector exists but nothing is connected (a display may
// come), false with `error` set when the name matches nothing.
int choose_connector(const std::vector<Connector>& connectors, std::string_view wanted, bool& waiting, std::string& error);
// The mode of `connector` the request names, or -1 with `error` listing what it offers.
int choose_mode(const Connector& connector, const ModeRequest& request, std::string& error);

// --drm-connector and --drm-mode together, as the start and every hotplug apply them.
struct Choice {
  enum class Outcome : std::uint8_t {
    chosen,             // `connector` and `mode` index the connectors and that connector's modes
    waiting,            // the wanted connector has no display (yet): `why` says which
    no_such_connector,  // `why` lists the connectors there are
    no_such_mode,       // `why` lists the modes the display offers
  } outcome = Outcome::waiting;
  int connector = -1, mode = -1;
  std::string why;
};
Choice choose_output(const std::vector<Connector>& connectors, std::string_view wanted_connector, const ModeRequest& wanted_mode);

// Every connector with its state and modes, one per line, for --drm-connector help and for errors
// where nothing fits.
std::string describe_connectors(std::string_view device, const std::vector<Connector>& connectors);

}  // namespace platform::kms
