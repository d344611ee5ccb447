#include "kms_device.h"

#include "backends.h"

#include "base/errno_text.h"

#include <fcntl.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <utility>

namespace platform {
namespace kms {
namespace {

std::string connector_name(const drmModeConnector& connector) {
  const char* type = drmModeGetConnectorTypeName(connector.connector_type);
  return std::string(type != nullptr ? type : "Unknown") + "-" + std::to_string(connector.connector_type_id);
}

struct FoundProperty {
  bool found = false;
  std::uint32_t id = 0;
  std::uint64_t value = 0;
};

FoundProperty find_property(int fd, std::uint32_t object, std::uint32_t type, const char* name) {
  PropertiesPtr properties(drmModeObjectGetProperties(fd, object, type));
  if (!properties) return {};
  for (std::uint32_t i = 0; i < properties->count_props; ++i) {
    PropertyPtr property(drmModeGetProperty(fd, properties->props[i]));
    if (property && std::strcmp(property->name, name) == 0) return {true, property->prop_id, properties->prop_values[i]};
  }
  return {};
}

bool has_connected_display(int fd) {
  Probe found;
  std::string ignored;
  if (!probe(fd, found, ignored)) return false;
  bool waiting = false;
  return choose_connector(found.connectors, "auto", waiting, ignored) >= 0;
}

}  // namespace

Mode to_mode(const drmModeModeInfo& info) {
  Mode mode;
  mode.width = info.hdisplay;
  mode.height = info.vdisplay;
  const double totals = static_cast<double>(info.htotal) * static_cast<double>(info.vtotal);
  mode.refresh_hz = totals > 0.0 ? static_cast<double>(info.clock) * 1000.0 / totals : static_cast<double>(info.vrefresh);
  mode.interlaced = (info.flags & DRM_MODE_FLAG_INTERLACE) != 0;
  if (mode.interlaced) mode.refresh_hz *= 2.0;
  mode.preferred = (info.type & DRM_MODE_TYPE_PREFERRED) != 0;
  return mode;
}

std::uint32_t property_id(int fd, std::uint32_t object, std::uint32_t type, const char* name) {
  return find_property(fd, object, type, name).id;
}

std::uint64_t property_value(int fd, std::uint32_t object, std::uint32_t type, const char* name, std::uint64_t fallback) {
  const FoundProperty property = find_property(fd, object, type, name);
  return property.found ? property.value : fallback;
}

bool probe(int fd, Probe& out, std::string& error) {
  out = {};
  ResourcesPtr resources(drmModeGetResources(fd));
  if (!resources) {
    error = "drmModeGetResources failed (" + base::errno_text(errno) + "): not a KMS device";
    return false;
  }
  for (int i = 0; i < resources->count_connectors; ++i) {
    ConnectorPtr raw(drmModeGetConnector(fd, resources->connectors[i]));
    if (!raw) continue;
    if (raw->connector_type == DRM_MODE_CONNECTOR_WRITEBACK) {
      out.writeback = raw->connector_id;
      continue;
    }
    Connector connector;
    connector.id = raw->connector_id;
    connector.name = connector_name(*raw);
    connector.state = raw->connection == DRM_MODE_CONNECTED      ? ConnectorState::connected
                      : raw->connection == DRM_MODE_DISCONNECTED ? ConnectorState::disconnected
                                                                 : ConnectorState::unknown;
    std::vector<drmModeModeInfo> raw_modes(raw->modes, raw->modes + raw->count_modes);
    for (const drmModeModeInfo& info : raw_modes) connector.modes.push_back(to_mode(info));
    out.connectors.push_back(std::move(connector));
    out.raw_modes.push_back(std::move(raw_modes));
  }
  return true;
}

bool find_crtc(int fd, std::uint32_t connector_id, std::uint32_t& crtc, int& crtc_index) {
  ResourcesPtr resources(drmModeGetResources(fd));
  // Current state only: the connector was just probed, and a probe reads the display's EDID again.
  ConnectorPtr connector(drmModeGetConnectorCurrent(fd, connector_id));
  if (!resources || !connector) return false;
  auto index_of = [&](std::uint32_t id) {
    for (int i = 0; i < resources->count_crtcs; ++i)
      if (resources->crtcs[i] == id) return i;
    return -1;
  };
  if (connector->encoder_id != 0) {
    EncoderPtr encoder(drmModeGetEncoder(fd, connector->encoder_id));
    if (encoder && encoder->crtc_id != 0 && index_of(encoder->crtc_id) >= 0) {
      crtc = encoder->crtc_id;
      crtc_index = index_of(crtc);
      return true;
    }
  }
  for (int e = 0; e < connector->count_encoders; ++e) {
    EncoderPtr encoder(drmModeGetEncoder(fd, connector->encoders[e]));
    if (!encoder) continue;
    for (int i = 0; i < resources->count_crtcs; ++i)
      if ((encoder->possible_crtcs & (1u << i)) != 0) {
        crtc = resources->crtcs[i];
        crtc_index = i;
        return true;
      }
  }
  return false;
}

std::uint32_t find_primary_plane(int fd, int crtc_index) {
  PlaneResourcesPtr planes(drmModeGetPlaneResources(fd));
  if (!planes) return 0;
  for (std::uint32_t i = 0; i < planes->count_planes; ++i) {
    PlanePtr plane(drmModeGetPlane(fd, planes->planes[i]));
    if (!plane || (plane->possible_crtcs & (1u << crtc_index)) == 0) continue;
    if (property_value(fd, plane->plane_id, DRM_MODE_OBJECT_PLANE, "type", UINT64_MAX) == DRM_PLANE_TYPE_PRIMARY)
      return plane->plane_id;
  }
  return 0;
}

bool has_kms(int fd) {
  ResourcesPtr resources(drmModeGetResources(fd));
  return resources && resources->count_connectors > 0 && resources->count_crtcs > 0;
}

std::vector<std::string> primary_nodes() {
  std::vector<std::string> nodes;
  drmDevicePtr devices[16];
  const int count = drmGetDevices2(0, devices, 16);
  if (count <= 0) return nodes;
  for (int i = 0; i < count; ++i)
    if ((devices[i]->available_nodes & (1 << DRM_NODE_PRIMARY)) != 0) nodes.emplace_back(devices[i]->nodes[DRM_NODE_PRIMARY]);
  drmFreeDevices(devices, count);
  return nodes;
}

base::UniqueFd open_node(const std::string& path) {
  return base::UniqueFd(open(path.c_str(), O_RDWR | O_CLOEXEC));
}

bool open_device(const std::string& wanted, base::UniqueFd& fd, std::string& path, std::string& error) {
  if (!wanted.empty()) {
    fd = open_node(wanted);
    if (!fd) {
      error = "--drm-device: cannot open " + wanted + " (" + base::errno_text(errno) + ")";
      return false;
    }
    if (!has_kms(fd.get())) {
      error = "--drm-device: " + wanted + " has no KMS connectors and CRTCs (a render-only GPU?)";
      return false;
    }
    char resolved[PATH_MAX];
    path = realpath(wanted.c_str(), resolved) != nullptr ? resolved : wanted;
    return true;
  }
  const std::vector<std::string> nodes = primary_nodes();
  std::string fallback, tried;
  for (const std::string& node : nodes) {
    base::UniqueFd candidate = open_node(node);
    if (!candidate) {
      tried += " " + node + " (" + base::errno_text(errno) + ")";
      continue;
    }
    if (!has_kms(candidate.get())) {
      tried += " " + node + " (no KMS)";
      continue;
    }
    if (has_connected_display(candidate.get())) {
      fd = std::move(candidate);
      path = node;
      return true;
    }
    if (fallback.empty()) fallback = node;
  }
  if (!fallback.empty()) {
    fd = open_node(fallback);
    path = fallback;
    if (fd) return true;
  }
  error = "no DRM device drives a display (" + (nodes.empty() ? std::string("no /dev/dri/card* found") : "tried:" + tried) +
          "); --drm-device names one";
  return false;
}

bool enable_client_caps(int fd, bool allow_atomic) {
  drmSetClientCap(fd, DRM_CLIENT_CAP_UNIVERSAL_PLANES, 1);
  const bool atomic = allow_atomic && drmSetClientCap(fd, DRM_CLIENT_CAP_ATOMIC, 1) == 0;
  if (atomic) drmSetClientCap(fd, DRM_CLIENT_CAP_WRITEBACK_CONNECTORS, 1);
  return atomic;
}

}  // namespace kms

bool find_kms_device(std::string& path) {
  for (const std::string& node : kms::primary_nodes()) {
    base::UniqueFd fd = kms::open_node(node);
    if (fd && kms::has_kms(fd.get())) {
      path = node;
      return true;
    }
  }
  return false;
}

bool describe_kms_outputs(const Options& options, std::string& text, std::string& error) {
  std::vector<std::string> nodes;
  if (!options.drm_device.empty())
    nodes.push_back(options.drm_device);
  else
    nodes = kms::primary_nodes();
  if (nodes.empty()) {
    error = "kms: no DRM device (no /dev/dri/card*)";
    return false;
  }
  text.clear();
  for (const std::string& node : nodes) {
    base::UniqueFd fd = kms::open_node(node);
    if (!fd && !options.drm_device.empty()) {
      error = "kms: --drm-device: cannot open " + node + " (" + base::errno_text(errno) + ")";
      return false;
    }
    if (!fd) {
      text += node + ": cannot open (" + base::errno_text(errno) + ")\n";
      continue;
    }
    const bool atomic = kms::enable_client_caps(fd.get(), true);
    kms::Probe found;
    std::string why;
    if (!kms::probe(fd.get(), found, why)) {
      text += node + ": " + why + "\n";
      continue;
    }
    text += kms::describe_connectors(node + (atomic ? " (atomic)" : " (legacy)"), found.connectors);
    if (found.writeback != 0) text += "  and a writeback connector (captures what is shown)\n";
  }
  return true;
}

}  // namespace platform
