#pragma once
// The DRM device and what it reports: finding the node that drives a display, reading its
// connectors (mpv's drm_common, kmscube's drm-common), the CRTC and primary plane for a connector,
// and property ids. libdrm's allocations are owned by unique_ptrs that free them with libdrm.
#include "kms_output.h"

#include "base/unique_fd.h"

#include <xf86drm.h>
#include <xf86drmMode.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace platform::kms {

template <class T, void (*Free)(T*)>
struct DrmFree {
  void operator()(T* p) const {
    if (p != nullptr) Free(p);
  }
};
using ResourcesPtr = std::unique_ptr<drmModeRes, DrmFree<drmModeRes, drmModeFreeResources>>;
using ConnectorPtr = std::unique_ptr<drmModeConnector, DrmFree<drmModeConnector, drmModeFreeConnector>>;
using EncoderPtr = std::unique_ptr<drmModeEncoder, DrmFree<drmModeEncoder, drmModeFreeEncoder>>;
using PlaneResourcesPtr = std::unique_ptr<drmModePlaneRes, DrmFree<drmModePlaneRes, drmModeFreePlaneResources>>;
using PlanePtr = std::unique_ptr<drmModePlane, DrmFree<drmModePlane, drmModeFreePlane>>;
using PropertiesPtr = std::unique_ptr<drmModeObjectProperties, DrmFree<drmModeObjectProperties, drmModeFreeObjectProperties>>;
using PropertyPtr = std::unique_ptr<drmModePropertyRes, DrmFree<drmModePropertyRes, drmModeFreeProperty>>;
using AtomicPtr = std::unique_ptr<drmModeAtomicReq, DrmFree<drmModeAtomicReq, drmModeAtomicFree>>;

// The id of the property `name` of a DRM object, or 0 where it has none.
std::uint32_t property_id(int fd, std::uint32_t object, std::uint32_t type, const char* name);
// Its current value, or `fallback`.
std::uint64_t property_value(int fd, std::uint32_t object, std::uint32_t type, const char* name, std::uint64_t fallback);

// A kernel mode as the choice reads it: refresh from the pixel clock, interlacing, preference.
Mode to_mode(const drmModeModeInfo& info);

// What the device's connectors say now (a full probe: the kernel asks the display), with the raw
// modes the kernel needs back, and the writeback connector where the driver has one.
struct Probe {
  std::vector<Connector> connectors;
  std::vector<std::vector<drmModeModeInfo>> raw_modes;
  std::uint32_t writeback = 0;
};
bool probe(int fd, Probe& out, std::string& error);

// The CRTC for a connector: the one it drives now, else the first its encoders can reach.
bool find_crtc(int fd, std::uint32_t connector_id, std::uint32_t& crtc, int& crtc_index);
// The primary plane that can show on the CRTC at `crtc_index`; 0 where none (or no atomic types).
std::uint32_t find_primary_plane(int fd, int crtc_index);

base::UniqueFd open_node(const std::string& path);
// Primary nodes of every DRM device, in the kernel's order.
std::vector<std::string> primary_nodes();
bool has_kms(int fd);
// The device to drive: the one named, else the first with KMS and a connected display, else the
// first with KMS (a display may be plugged in later). Card numbers change between boots, so the
// choice is by capability.
bool open_device(const std::string& wanted, base::UniqueFd& fd, std::string& path, std::string& error);
// Universal planes always; atomic commits (and with them writeback connectors) when `allow_atomic`
// and the driver offers them. Returns whether atomic commits are on.
bool enable_client_caps(int fd, bool allow_atomic);

}  // namespace platform::kms
