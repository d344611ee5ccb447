#include "kms_writeback.h"

#include "kms_device.h"

#include "base/errno_text.h"

#include <drm_fourcc.h>
#include <poll.h>
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>

namespace platform::kms {
namespace {

// XRGB8888 is B, G, R, X in memory; rows `pitch` bytes apart.
void xrgb_to_rgba(const std::uint8_t* source, std::uint32_t pitch, std::uint32_t width, std::uint32_t height,
                  std::vector<std::uint8_t>& rgba) {
  rgba.resize(static_cast<size_t>(width) * height * 4);
  for (std::uint32_t y = 0; y < height; ++y)
    for (std::uint32_t x = 0; x < width; ++x) {
      const std::uint8_t* in = source + static_cast<size_t>(y) * pitch + x * 4;
      std::uint8_t* pixel = &rgba[(static_cast<size_t>(y) * width + x) * 4];
      pixel[0] = in[2];
      pixel[1] = in[1];
      pixel[2] = in[0];
      pixel[3] = 255;
    }
}

using SteadyClock = std::chrono::steady_clock;

// Nonblocking, so that a driver whose commit never completes costs an error and not the process:
// a blocking commit waits in the kernel, where no timeout of ours reaches. A nonblocking commit is
// refused with EBUSY while the one before it is still in flight; that is waited out, up to `deadline`.
// 0, or the errno of the refusal.
int commit_nonblocking(int fd, drmModeAtomicReq* request, SteadyClock::time_point deadline) {
  for (;;) {
    if (drmModeAtomicCommit(fd, request, DRM_MODE_ATOMIC_ALLOW_MODESET | DRM_MODE_ATOMIC_NONBLOCK, nullptr) == 0) return 0;
    const int code = errno;
    if ((code != EBUSY && code != EINTR) || SteadyClock::now() >= deadline) return code;
    poll(nullptr, 0, 2);
  }
}

}  // namespace

bool capture_writeback(const WritebackCapture& capture, std::vector<std::uint8_t>& rgba, std::string& error,
                       bool& needs_modeset) {
  const int fd = capture.fd;
  const std::uint32_t width = static_cast<std::uint32_t>(capture.width), height = static_cast<std::uint32_t>(capture.height);
  const std::string what = "the writeback connector on CRTC " + std::to_string(capture.crtc) + " at " + std::to_string(width) +
                           "x" + std::to_string(height) + " XRGB8888";
  std::uint32_t handle = 0, pitch = 0, fb = 0;
  std::uint64_t bytes = 0, offset = 0;
  if (drmModeCreateDumbBuffer(fd, width, height, 32, 0, &handle, &pitch, &bytes) != 0) {
    error = "kms: no dumb buffer for " + what + " (" + base::errno_text(errno) + ")";
    return false;
  }
  const std::uint32_t handles[4] = {handle}, pitches[4] = {pitch}, offsets[4] = {};
  bool ok = drmModeAddFB2(fd, width, height, DRM_FORMAT_XRGB8888, handles, pitches, offsets, &fb, 0) == 0;
  if (!ok) error = "kms: no framebuffer for " + what + " (drmModeAddFB2: " + base::errno_text(errno) + ")";
  const std::uint32_t crtc_prop = property_id(fd, capture.writeback, DRM_MODE_OBJECT_CONNECTOR, "CRTC_ID");
  const std::uint32_t fb_prop = property_id(fd, capture.writeback, DRM_MODE_OBJECT_CONNECTOR, "WRITEBACK_FB_ID");
  const std::uint32_t fence_prop = property_id(fd, capture.writeback, DRM_MODE_OBJECT_CONNECTOR, "WRITEBACK_OUT_FENCE_PTR");
  std::int32_t fence = -1;
  bool detached_display = false;
  const SteadyClock::time_point deadline = SteadyClock::now() + std::chrono::milliseconds(capture.timeout_ms);
  int code = 0;
  if (ok) {
    // Beside the display where the driver can clone; where it cannot (vkms on 6.1 refuses two
    // encoders on one CRTC), the display connector is detached for the capture: the CRTC still
    // composes the same planes, so what the writeback sees is what was being scanned out.
    for (const bool detach : {false, true}) {
      AtomicPtr request(drmModeAtomicAlloc());
      if (detach) drmModeAtomicAddProperty(request.get(), capture.display_connector, capture.display_connector_crtc, 0);
      drmModeAtomicAddProperty(request.get(), capture.writeback, crtc_prop, capture.crtc);
      drmModeAtomicAddProperty(request.get(), capture.writeback, fb_prop, fb);
      drmModeAtomicAddProperty(request.get(), capture.writeback, fence_prop, reinterpret_cast<std::uintptr_t>(&fence));
      fence = -1;
      code = commit_nonblocking(fd, request.get(), deadline);
      ok = code == 0;
      detached_display = detach;
      if (ok || code != EINVAL) break;
    }
    if (!ok)
      error = "kms: the commit attaching " + what + " was refused (" + base::errno_text(code) + ")" +
              (detached_display ? ", beside " + capture.display_name + " and without it" : std::string());
  }
  if (ok && fence < 0) {
    ok = false;
    error = "kms: the commit attaching " + what + " gave no out-fence to wait on";
  }
  if (ok) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - SteadyClock::now()).count();
    pollfd wait{fence, POLLIN, 0};
    ok = poll(&wait, 1, static_cast<int>(std::max<std::int64_t>(left, 0))) == 1;
    if (!ok) error = "kms: " + what + " did not complete within " + std::to_string(capture.timeout_ms) + " ms";
  }
  if (fence >= 0) close(fence);
  if (ok) {
    ok = drmModeMapDumbBuffer(fd, handle, &offset) == 0;
    void* mapped = ok ? mmap(nullptr, bytes, PROT_READ, MAP_SHARED, fd, static_cast<off_t>(offset)) : MAP_FAILED;
    if (mapped == MAP_FAILED) {
      ok = false;
      error = "kms: cannot map the buffer of " + what + " (" + base::errno_text(errno) + ")";
    } else {
      xrgb_to_rgba(static_cast<const std::uint8_t*>(mapped), pitch, width, height, rgba);
      munmap(mapped, bytes);
    }
  }
  // Detached again (and the display attached again), so the next flips commit the primary plane alone.
  AtomicPtr restore(drmModeAtomicAlloc());
  drmModeAtomicAddProperty(restore.get(), capture.writeback, crtc_prop, 0);
  drmModeAtomicAddProperty(restore.get(), capture.writeback, fb_prop, 0);
  if (detached_display)
    drmModeAtomicAddProperty(restore.get(), capture.display_connector, capture.display_connector_crtc, capture.crtc);
  // Its own deadline: the capture's may be spent, and a display left detached costs more than a wait.
  if (commit_nonblocking(fd, restore.get(), SteadyClock::now() + std::chrono::milliseconds(capture.timeout_ms)) != 0)
    needs_modeset = true;
  if (fb != 0) drmModeRmFB(fd, fb);
  drmModeDestroyDumbBuffer(fd, handle);
  return ok;
}

}  // namespace platform::kms
