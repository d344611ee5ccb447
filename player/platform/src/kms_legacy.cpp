// Legacy modesetting: drmModeSetCrtc for a mode, drmModePageFlip for each frame. What drivers
// without atomic support take, and what --drm-atomic no chooses.
#include "kms_commit.h"
#include "kms_device.h"

#include <xf86drm.h>

#include <cerrno>

namespace platform::kms {
namespace {

class LegacyCommit final : public Commit {
 public:
  LegacyCommit(int fd, std::uint32_t driven_crtc) : fd_(fd), driven_crtc_(driven_crtc) {}

  const Kind& kind() const override {
    static constexpr Kind kLegacy{"legacy", "drmModeSetCrtc to ", "drmModePageFlip on ", false};
    return kLegacy;
  }

  Prepared prepare(const Target& target, std::string& error) override {
    (void)error;
    target_ = target;
    return Prepared::ready;
  }

  bool modeset(std::uint32_t fb, int& error_code) override {
    // What a hotplug moved the output away from is switched off first.
    if (driven_crtc_ != 0 && driven_crtc_ != target_.crtc) drmModeSetCrtc(fd_, driven_crtc_, 0, 0, 0, nullptr, 0, nullptr);
    std::uint32_t connector = target_.connector;
    const int result = drmModeSetCrtc(fd_, target_.crtc, fb, 0, 0, &connector, 1, &target_.mode);
    error_code = result == 0 ? 0 : errno;
    if (result == 0) driven_crtc_ = target_.crtc;
    return result == 0;
  }

  bool flip(std::uint32_t fb, std::uint64_t sequence, int& error_code) override {
    void* user_data = reinterpret_cast<void*>(static_cast<std::uintptr_t>(sequence));
    const int result = drmModePageFlip(fd_, target_.crtc, fb, DRM_MODE_PAGE_FLIP_EVENT, user_data);
    error_code = result == 0 ? 0 : errno;
    return result == 0;
  }

  bool power_off(int& error_code) override { return set_dpms(DRM_MODE_DPMS_OFF, error_code); }
  bool power_on(int& error_code) override { return set_dpms(DRM_MODE_DPMS_ON, error_code); }
  std::optional<bool> powered() const override {
    constexpr std::uint64_t kUnread = ~std::uint64_t{0};
    const std::uint64_t dpms = property_value(fd_, target_.connector, DRM_MODE_OBJECT_CONNECTOR, "DPMS", kUnread);
    return dpms == kUnread ? std::nullopt : std::optional<bool>(dpms == DRM_MODE_DPMS_ON);
  }

  std::uint32_t driven_crtc() const override { return driven_crtc_; }

 private:
  bool set_dpms(std::uint64_t level, int& error_code) {
    const std::uint32_t dpms = property_id(fd_, target_.connector, DRM_MODE_OBJECT_CONNECTOR, "DPMS");
    if (dpms == 0) {
      error_code = ENOTSUP;  // a connector without the property cannot be switched off this way
      return false;
    }
    const int result = drmModeConnectorSetProperty(fd_, target_.connector, dpms, level);
    error_code = result == 0 ? 0 : errno;
    return result == 0;
  }

  int fd_;
  Target target_;
  std::uint32_t driven_crtc_;
};

}  // namespace

std::unique_ptr<Commit> make_legacy_commit(int fd, std::uint32_t driven_crtc) {
  return std::make_unique<LegacyCommit>(fd, driven_crtc);
}

}  // namespace platform::kms
