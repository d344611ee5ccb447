#include "kms_output.h"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace platform::kms {
namespace {

bool parse_int(std::string_view text, int& out) {
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc{} && end == text.data() + text.size() && out > 0;
}

bool parse_hz(std::string_view text, double& out) {
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc{} && end == text.data() + text.size() && std::isfinite(out) && out > 0.0 && out < 1000.0;
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
  if (text == "preferred") return true;
  if (text == "highest") {
    out.kind = ModeRequest::Kind::highest;
    return true;
  }
  const size_t x = text.find('x');
  const size_t at = text.find('@');
  const std::string_view width = x == std::string_view::npos ? std::string_view{} : text.substr(0, x);
  const std::string_view height = x == std::string_view::npos ? std::string_view{}
                                                               : text.substr(x + 1, at == std::string_view::npos ? std::string_view::npos : at - x - 1);
  out.kind = ModeRequest::Kind::size;
  if (!parse_int(width, out.width) || !parse_int(height, out.height) ||
      (at != std::string_view::npos && !parse_hz(text.substr(at + 1), out.refresh_hz))) {
    error = "--drm-mode: expected preferred, highest or WxH[@R] (e.g. 1920x1080@60), got '" + std::string(text) + "'";
    out = {};
    return false;
  }
  return true;
}

std::string to_string(const ModeRequest& request) {
  switch (request.kind) {
    case ModeRequest::Kind::preferred: return "preferred";
    case ModeRequest::Kind::highest: return "highest";
    case ModeRequest::Kind::size: {
      std::string text = std::to_string(request.width) + "x" + std::to_string(request.height);
      if (request.refresh_hz > 0.0) {
        char hz[32];
        std::snprintf(hz, sizeof hz, "@%g", request.refresh_hz);
        text += hz;
      }
      return text;
    }
  }
  return "?";
}

std::string_view to_string(ConnectorState state) {
  switch (state) {
    case ConnectorState::connected: return "connected";
    case ConnectorState::disconnected: return "disconnected";
    case ConnectorState::unknown: return "unknown";
  }
  return "?";
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
    error = "--drm-mode: " + connector.name + " offers no mode " + to_string(request) + " (it offers " + modes_text(connector) + ")";
  return best;
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
