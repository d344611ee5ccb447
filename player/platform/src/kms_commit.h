#pragma once
// How frames reach the display: atomic commits (kms_atomic.cpp) or the legacy SetCrtc/PageFlip
// calls (kms_legacy.cpp), behind one interface chosen once at start, as kmscube's drm-atomic.c and
// drm-legacy.c sit behind its struct drm. The platform never asks which one it holds.
#include <xf86drmMode.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace platform::kms {

// What a commit drives: the connector, its CRTC and the mode.
struct Target {
  std::uint32_t connector = 0;
  std::uint32_t crtc = 0;
  int crtc_index = -1;
  drmModeModeInfo mode{};
};

class Commit {
 public:
  enum class Prepared : std::uint8_t { ready, failed, unsupported };
  // What a kind of commit is called in descriptions and errors, and what it can do.
  struct Kind {
    std::string_view modesetting;  // "atomic", "legacy"
    std::string_view modeset;      // "an atomic modeset to ", "drmModeSetCrtc to "
    std::string_view flip;         // "an atomic page flip on ", "drmModePageFlip on "
    bool writeback;                // a writeback connector is attached by an atomic commit only
  };

  virtual ~Commit() = default;
  virtual const Kind& kind() const = 0;
  // Readies commits to `target` (property ids, the mode as a blob); the next commit is a modeset.
  // `unsupported`: this kind cannot drive it at all (a driver's atomic interface lacking what a
  // modeset needs), and legacy commits should; `failed` says why in `error`.
  virtual Prepared prepare(const Target& target, std::string& error) = 0;
  // Shows `fb` in the target's mode, switching off what an earlier modeset drove elsewhere.
  // Blocking. False with errno's code.
  virtual bool modeset(std::uint32_t fb, int& error_code) = 0;
  // Switches the display off and keeps what is driven (atomic: the CRTC's ACTIVE to 0; legacy: the
  // connector's DPMS to off); the next modeset switches it on again. Blocking. False with errno's code.
  virtual bool power_off(int& error_code) = 0;
  // Legacy: the connector's DPMS back on before the modeset that follows (atomic: ACTIVE=1 is part of
  // every modeset). False with errno's code.
  virtual bool power_on(int& error_code) {
    error_code = 0;
    return true;
  }
  // Whether the driven CRTC is on, as the kernel has it (atomic: its ACTIVE property; legacy: the
  // connector's DPMS): what the log and the vm tier check a power change by. None where unreadable.
  virtual std::optional<bool> powered() const = 0;
  // Queues `fb` for the next vblank; its page-flip event carries `sequence` as user data.
  virtual bool flip(std::uint32_t fb, std::uint64_t sequence, int& error_code) = 0;
  // The CRTC the last successful modeset drove, for a kind that takes over from this one.
  virtual std::uint32_t driven_crtc() const = 0;
  // Atomic only: the id of the driven connector's CRTC_ID property, with which a writeback capture
  // detaches and reattaches the display; 0 where commits have no properties.
  virtual std::uint32_t connector_crtc_property() const { return 0; }
};

std::unique_ptr<Commit> make_atomic_commit(int fd);
// `driven_crtc`: what an atomic commit drove before this one takes over, switched off at its modeset.
std::unique_ptr<Commit> make_legacy_commit(int fd, std::uint32_t driven_crtc = 0);

}  // namespace platform::kms
