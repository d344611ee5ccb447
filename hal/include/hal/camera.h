#pragma once
#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

#include "hal/image.h"

namespace hal {

enum class CameraState : std::uint8_t {
  closed,     // never opened or closed on purpose
  streaming,  // frames can be read
  lost,       // device vanished or failed; reopen is retried periodically
};
std::string_view to_string(CameraState s);

enum class PixelFormat : std::uint8_t { automatic, mjpeg, yuyv, rgb24 };
std::string_view to_string(PixelFormat f);
bool parse_pixel_format(std::string_view text, PixelFormat& out);
std::string pixel_format_names();  // "auto, mjpeg, yuyv, rgb24"

struct CameraConfig {
  std::string device;  // a path; /dev/v4l/by-id/... or by-path/... survive re-enumeration
  int width = 1280;
  int height = 720;
  PixelFormat format = PixelFormat::automatic;  // MJPEG, then YUYV
  int buffers = 4;
  std::chrono::milliseconds reopen_interval{2000};
  // No usable frame for this long while streaming (a wedged camera, or one gone without an error):
  // torn down and reopened like an unplugged one. Webcams deliver at 5 fps or more even in the dark.
  std::chrono::milliseconds frame_timeout{2000};
};

class Camera {
 public:
  virtual ~Camera() = default;
  // Readable when a frame is ready or a deadline (reopen, no-frame check) is due; then call
  // read_frame() and service().
  virtual int fd() const = 0;
  virtual CameraState state() const = 0;
  // The last error, naming the device and what failed; empty when none.
  virtual const std::string& last_error() const = 0;
  // Non-blocking: true and `out` filled (buffer reused) when a frame was ready.
  virtual bool read_frame(RgbImage& out) = 0;
  // Gives up on a stream that delivered no frame for frame_timeout, and retries a lost device when
  // its reopen timer is due.
  virtual void service() = 0;
  // Waits up to `timeout` for one frame (for checks and hal-test, not the frame loop).
  bool capture(RgbImage& out, std::chrono::milliseconds timeout);
};

}  // namespace hal
