// Atomic modesetting: a modeset is one commit of the connector, CRTC and primary plane properties
// (and of switching off what was driven before); a flip is one property, FB_ID, committed without
// blocking. What the writeback capture builds on, and the default where the driver offers it.
#include "kms_commit.h"
#include "kms_device.h"

#include "base/errno_text.h"

#include <xf86drm.h>

#include <cerrno>
#include <utility>
#include <vector>

namespace platform::kms {
namespace {

struct Properties {
  std::uint32_t connector_crtc = 0, crtc_mode = 0, crtc_active = 0, plane_fb = 0, plane_crtc = 0, src_x = 0, src_y = 0, src_w = 0,
                src_h = 0, crtc_x = 0, crtc_y = 0, crtc_w = 0, crtc_h = 0;
};

// Every property a modeset sets; false where the driver lacks one.
bool read_properties(int fd, const Target& target, std::uint32_t plane, Properties& out) {
  struct Wanted {
    std::uint32_t object, type;
    const char* name;
    std::uint32_t Properties::*member;
  };
  const Wanted wanted[] = {
      {target.connector, DRM_MODE_OBJECT_CONNECTOR, "CRTC_ID", &Properties::connector_crtc},
      {target.crtc, DRM_MODE_OBJECT_CRTC, "MODE_ID", &Properties::crtc_mode},
      {target.crtc, DRM_MODE_OBJECT_CRTC, "ACTIVE", &Properties::crtc_active},
      {plane, DRM_MODE_OBJECT_PLANE, "FB_ID", &Properties::plane_fb},
      {plane, DRM_MODE_OBJECT_PLANE, "CRTC_ID", &Properties::plane_crtc},
      {plane, DRM_MODE_OBJECT_PLANE, "SRC_X", &Properties::src_x},
      {plane, DRM_MODE_OBJECT_PLANE, "SRC_Y", &Properties::src_y},
      {plane, DRM_MODE_OBJECT_PLANE, "SRC_W", &Properties::src_w},
      {plane, DRM_MODE_OBJECT_PLANE, "SRC_H", &Properties::src_h},
      {plane, DRM_MODE_OBJECT_PLANE, "CRTC_X", &Properties::crtc_x},
      {plane, DRM_MODE_OBJECT_PLANE, "CRTC_Y", &Properties::crtc_y},
      {plane, DRM_MODE_OBJECT_PLANE, "CRTC_W", &Properties::crtc_w},
      {plane, DRM_MODE_OBJECT_PLANE, "CRTC_H", &Properties::crtc_h},
  };
  bool complete = true;
  for (const Wanted& property : wanted)
    complete = (out.*property.member = property_id(fd, property.object, property.type, property.name)) != 0 && complete;
  return complete;
}

class AtomicCommit final : public Commit {
 public:
  explicit AtomicCommit(int fd) : fd_(fd) {}
  ~AtomicCommit() override {
    if (mode_blob_ != 0) drmModeDestroyPropertyBlob(fd_, mode_blob_);
  }
  AtomicCommit(const AtomicCommit&) = delete;
  AtomicCommit& operator=(const AtomicCommit&) = delete;

  const Kind& kind() const override {
    static constexpr Kind kAtomic{"atomic", "an atomic modeset to ", "an atomic page flip on ", true};
    return kAtomic;
  }
  Prepared prepare(const Target& target, std::string& error) override;
  bool modeset(std::uint32_t fb, int& error_code) override;
  bool flip(std::uint32_t fb, std::uint64_t sequence, int& error_code) override;
  bool power_off(int& error_code) override;
  std::optional<bool> powered() const override;
  std::uint32_t driven_crtc() const override { return driven_.crtc; }
  std::uint32_t connector_crtc_property() const override { return props_.connector_crtc; }

 private:
  // Other planes (overlays, cursors) another client left on this CRTC: switched off at the modeset.
  struct OtherPlane {
    std::uint32_t id = 0, fb_prop = 0, crtc_prop = 0;
  };

  int fd_;
  Target target_;
  std::uint32_t plane_ = 0, mode_blob_ = 0;
  Properties props_;
  std::vector<OtherPlane> other_planes_;
  // What the last modeset drove, switched off when a hotplug moves the output elsewhere.
  Target driven_;
  std::uint32_t driven_plane_ = 0;
  Properties driven_props_;
  AtomicPtr request_{drmModeAtomicAlloc()};  // for modesets; a flip is one ioctl on arrays of its own
};

Commit::Prepared AtomicCommit::prepare(const Target& target, std::string& error) {
  const std::uint32_t plane = find_primary_plane(fd_, target.crtc_index);
  Properties props;
  // A driver whose atomic interface lacks what a modeset needs: legacy does it.
  if (!read_properties(fd_, target, plane, props) || plane == 0 || !request_) return Prepared::unsupported;
  std::vector<OtherPlane> others;
  if (PlaneResourcesPtr planes{drmModeGetPlaneResources(fd_)}) {
    for (std::uint32_t i = 0; i < planes->count_planes; ++i) {
      const std::uint32_t id = planes->planes[i];
      if (id == plane) continue;
      PlanePtr other(drmModeGetPlane(fd_, id));
      if (other && other->crtc_id == target.crtc)
        others.push_back(
            {id, property_id(fd_, id, DRM_MODE_OBJECT_PLANE, "FB_ID"), property_id(fd_, id, DRM_MODE_OBJECT_PLANE, "CRTC_ID")});
    }
  }
  std::uint32_t blob = 0;
  if (drmModeCreatePropertyBlob(fd_, &target.mode, sizeof target.mode, &blob) != 0) {
    error = "kms: the mode " + describe(to_mode(target.mode)) + " could not be made a property blob (" + base::errno_text(errno) +
            ")";
    return Prepared::failed;
  }
  if (mode_blob_ != 0) drmModeDestroyPropertyBlob(fd_, mode_blob_);
  mode_blob_ = blob;
  target_ = target;
  plane_ = plane;
  props_ = props;
  other_planes_ = std::move(others);
  return Prepared::ready;
}

bool AtomicCommit::modeset(std::uint32_t fb, int& error_code) {
  drmModeAtomicReq* request = request_.get();
  drmModeAtomicSetCursor(request, 0);
  const auto add = [request](std::uint32_t object, std::uint32_t property, std::uint64_t value) {
    drmModeAtomicAddProperty(request, object, property, value);
  };
  // What a hotplug moved the output away from is switched off in the same commit.
  if (driven_.connector != 0 && driven_.connector != target_.connector) add(driven_.connector, driven_props_.connector_crtc, 0);
  if (driven_.crtc != 0 && driven_.crtc != target_.crtc) {
    add(driven_plane_, driven_props_.plane_fb, 0);
    add(driven_plane_, driven_props_.plane_crtc, 0);
    add(driven_.crtc, driven_props_.crtc_active, 0);
    add(driven_.crtc, driven_props_.crtc_mode, 0);
  }
  for (const OtherPlane& other : other_planes_) {
    add(other.id, other.fb_prop, 0);
    add(other.id, other.crtc_prop, 0);
  }
  add(target_.connector, props_.connector_crtc, target_.crtc);
  add(target_.crtc, props_.crtc_mode, mode_blob_);
  add(target_.crtc, props_.crtc_active, 1);
  const std::uint64_t w = target_.mode.hdisplay, h = target_.mode.vdisplay;
  // The whole framebuffer (source in 16.16 fixed point) onto the whole CRTC.
  const std::pair<std::uint32_t, std::uint64_t> plane_values[] = {{props_.plane_fb, fb},   {props_.plane_crtc, target_.crtc},
                                                                  {props_.src_x, 0},       {props_.src_y, 0},
                                                                  {props_.src_w, w << 16}, {props_.src_h, h << 16},
                                                                  {props_.crtc_x, 0},      {props_.crtc_y, 0},
                                                                  {props_.crtc_w, w},      {props_.crtc_h, h}};
  for (const auto& [property, value] : plane_values) add(plane_, property, value);
  const int result = drmModeAtomicCommit(fd_, request, DRM_MODE_ATOMIC_ALLOW_MODESET, nullptr);
  error_code = result == 0 ? 0 : errno;
  if (result != 0) return false;
  other_planes_.clear();
  driven_ = target_;
  driven_plane_ = plane_;
  driven_props_ = props_;
  return true;
}

bool AtomicCommit::power_off(int& error_code) {
  drmModeAtomicReq* request = request_.get();
  drmModeAtomicSetCursor(request, 0);
  // The mode, the connector and the plane stay as they are: a modeset with ACTIVE=1 shows them again.
  drmModeAtomicAddProperty(request, target_.crtc, props_.crtc_active, 0);
  const int result = drmModeAtomicCommit(fd_, request, DRM_MODE_ATOMIC_ALLOW_MODESET, nullptr);
  error_code = result == 0 ? 0 : errno;
  return result == 0;
}

std::optional<bool> AtomicCommit::powered() const {
  constexpr std::uint64_t kUnread = ~std::uint64_t{0};
  const std::uint64_t active = property_value(fd_, target_.crtc, DRM_MODE_OBJECT_CRTC, "ACTIVE", kUnread);
  return active == kUnread ? std::nullopt : std::optional<bool>(active != 0);
}

bool AtomicCommit::flip(std::uint32_t fb, std::uint64_t sequence, int& error_code) {
  // One plane, one property: the ioctl on arrays of its own, since libdrm's commit allocates.
  std::uint32_t objects[1] = {plane_}, counts[1] = {1}, properties[1] = {props_.plane_fb};
  std::uint64_t values[1] = {fb};
  drm_mode_atomic atomic{};
  // No in-fence: the buffer is complete when eglSwapBuffers returns on implicitly synchronised
  // drivers, and llvmpipe has no EGL_ANDROID_native_fence_sync to make one.
  atomic.flags = DRM_MODE_ATOMIC_NONBLOCK | DRM_MODE_PAGE_FLIP_EVENT;
  atomic.count_objs = 1;
  atomic.objs_ptr = reinterpret_cast<std::uintptr_t>(objects);
  atomic.count_props_ptr = reinterpret_cast<std::uintptr_t>(counts);
  atomic.props_ptr = reinterpret_cast<std::uintptr_t>(properties);
  atomic.prop_values_ptr = reinterpret_cast<std::uintptr_t>(values);
  atomic.user_data = sequence;
  const int result = drmIoctl(fd_, DRM_IOCTL_MODE_ATOMIC, &atomic);
  error_code = result == 0 ? 0 : errno;
  return result == 0;
}

}  // namespace

std::unique_ptr<Commit> make_atomic_commit(int fd) {
  return std::make_unique<AtomicCommit>(fd);
}

}  // namespace platform::kms
