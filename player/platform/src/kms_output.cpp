#include "kms_output.h"

#include "base/names.h"
#include "base/parse.h"

#include <climits>
#include <cmath>
#include <cstdio>

namespace platform::kms {
namespace {

// The kinds a word names; a size is WxH[@R].
constexpr base::Name<ModeRequest::Kind> kModeKindNames[] = {{ModeRequest::Kind::preferred, "preferred"},
                                                            {ModeRequest::Kind::highest, "highest"}};
static_assert(base::in_enum_order(kModeKindNames));

constexpr base::Name<ConnectorState> kConnectorStateNames[] = {{ConnectorState::connected, "connected"},
                                                               {ConnectorState::disconnected, "disconnected"},
                                                               {ConnectorState::unknown, "unknown"}};
static_assert(base::in_enum_order(kConnectorStateNames));

bool parse_hz(std::string_view text, double& out) {
  return base::parse_number(text, out) && out > 0.0 && out < 1000.0;
}

std::string modes_text(const Connector& connector) {
  if (connector.modes.empty()) return "no modes";
  std::string text;
  for (const Mode& mode : connector.modes) {
    text += (text.empty() ? "" : ", ") + describe(mode);
    if (mode.preferred) text += " (preferred)";
  }
  return text;
}

}  // namespace

bool parse_mode_request(std::string_view text, ModeRequest& out, std::string& error) {
  out = {};
  if (base::parse_name(kModeKindNames, text, out.kind)) return true;
  const size_t at = text.find('@');
  out.kind = ModeRequest::Kind::size;
  if (!base::parse_size(text.substr(0, at), INT_MAX, out.width, out.height) ||
      (at != std::string_view::npos && !parse_hz(text.substr(at + 1), out.refresh_hz))) {
    std::vector<std::string> forms = base::names_of(kModeKindNames);
    forms.emplace_back("WxH[@R]");
    error = "--drm-mode: expected " + base::join_names(forms, " or ") + " (e.g. 1920x1080@60), got '" + std::string(text) + "'";
    out = {};
    return false;
  }
  return true;
}

std::string to_string(const ModeRequest& request) {
  if (request.kind != ModeRequest::Kind::size) return std::string(base::name_of(kModeKindNames, request.kind));
  std::string text = std::to_string(request.width) + "x" + std::to_string(request.height);
  if (request.refresh_hz > 0.0) {
    char hz[32];
    std::snprintf(hz, sizeof hz, "@%g", request.refresh_hz);
    text += hz;
  }
  return text;
}

std::string_view to_string(ConnectorState state) {
  return base::name_of(kConnectorStateNames, state);
}

std::string describe(const Mode& mode) {
  char text[64];
  std::snprintf(text, sizeof text, "%dx%d%s@%.2f", mode.width, mode.height, mode.interlaced ? "i" : "", mode.refresh_hz);
  return text;
}

int choose_connector(const std::vector<Connector>& connectors, std::string_view wanted, bool& waiting, std::string& error) {
  waiting = false;
  if (wanted == "auto") {
    for (size_t i = 0; i < connectors.size(); ++i)
      if (connectors[i].state == ConnectorState::connected && !connectors[i].modes.empty()) return static_cast<int>(i);
    // "unknown" is what some drivers say of a display they cannot probe (no hotplug detect line):
    // with modes it is as good as connected.
    for (size_t i = 0; i < connectors.size(); ++i)
      if (connectors[i].state == ConnectorState::unknown && !connectors[i].modes.empty()) return static_cast<int>(i);
    waiting = true;
    return -1;
  }
  for (size_t i = 0; i < connectors.size(); ++i) {
    if (connectors[i].name != wanted) continue;
    if (connectors[i].state == ConnectorState::disconnected || connectors[i].modes.empty()) {
      waiting = true;
      return -1;
    }
    return static_cast<int>(i);
  }
  error = "--drm-connector: no connector named '" + std::string(wanted) + "' (expected auto, help or one of:";
  for (const Connector& connector : connectors) error += " " + connector.name;
  error += ")";
  return -1;
}

int choose_mode(const Connector& connector, const ModeRequest& request, std::string& error) {
  int best = -1;
  for (size_t i = 0; i < connector.modes.size(); ++i) {
    const Mode& mode = connector.modes[i];
    const Mode* current = best < 0 ? nullptr : &connector.modes[static_cast<size_t>(best)];
    switch (request.kind) {
      case ModeRequest::Kind::preferred:
        if (mode.preferred && (current == nullptr || !current->preferred)) best = static_cast<int>(i);
        break;
      case ModeRequest::Kind::highest: {
        const long long pixels = static_cast<long long>(mode.width) * mode.height;
        const long long current_pixels = current == nullptr ? -1 : static_cast<long long>(current->width) * current->height;
        if (pixels > current_pixels || (pixels == current_pixels && mode.refresh_hz > current->refresh_hz + 0.01))
          best = static_cast<int>(i);
        break;
      }
      case ModeRequest::Kind::size:
        if (mode.width != request.width || mode.height != request.height) break;
        if (request.refresh_hz > 0.0) {
          // Within half a hertz: 59.94 is what "@60" means to a user, 50 is not.
          const double error_hz = std::abs(mode.refresh_hz - request.refresh_hz);
          if (error_hz <= 0.5 && (current == nullptr || error_hz < std::abs(current->refresh_hz - request.refresh_hz)))
            best = static_cast<int>(i);
        } else if (current == nullptr || mode.refresh_hz > current->refresh_hz + 0.01 ||
                   (current->interlaced && !mode.interlaced)) {
          best = static_cast<int>(i);
        }
        break;
    }
  }
  // The kernel lists the preferred mode first where the display names none; so does mpv.
  if (best < 0 && request.kind == ModeRequest::Kind::preferred && !connector.modes.empty()) best = 0;
  if (best < 0)
    error =
        "--drm-mode: " + connector.name + " offers no mode " + to_string(request) + " (it offers " + modes_text(connector) + ")";
  return best;
}

Choice choose_output(const std::vector<Connector>& connectors, std::string_view wanted_connector,
                     const ModeRequest& wanted_mode) {
  Choice choice;
  bool waiting = false;
  choice.connector = choose_connector(connectors, wanted_connector, waiting, choice.why);
  if (choice.connector < 0) {
    choice.outcome = waiting ? Choice::Outcome::waiting : Choice::Outcome::no_such_connector;
    if (waiting)
      choice.why =
          wanted_connector == "auto" ? "no display connected" : "no display connected to " + std::string(wanted_connector);
    return choice;
  }
  choice.mode = choose_mode(connectors[static_cast<size_t>(choice.connector)], wanted_mode, choice.why);
  choice.outcome = choice.mode < 0 ? Choice::Outcome::no_such_mode : Choice::Outcome::chosen;
  return choice;
}

std::string describe_connectors(std::string_view device, const std::vector<Connector>& connectors) {
  std::string text = std::string(device) + ": " + std::to_string(connectors.size()) + " connector(s)";
  if (connectors.empty()) return text + "\n";
  text += "\n";
  for (const Connector& connector : connectors)
    text += "  " + connector.name + ": " + std::string(to_string(connector.state)) + "; " + modes_text(connector) + "\n";
  return text;
}

}  // namespace platform::kms
