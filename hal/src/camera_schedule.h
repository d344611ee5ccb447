#pragma once
// When a V4L2 camera gives up on its stream and when it retries, as a pure function of the time, so a
// manual clock drives it in tests without a device.
#include <algorithm>

#include "hal/clock.h"

namespace hal::detail {

class CameraSchedule {
 public:
  CameraSchedule(Nanos reopen_interval, Nanos frame_timeout) : reopen_interval_(reopen_interval), frame_timeout_(frame_timeout) {}

  // Streaming from `now`: the first frame must come within the frame timeout, as every later one.
  void opened(Nanos now) {
    streaming_ = true;
    last_frame_ = now;
  }
  void frame(Nanos now) { last_frame_ = std::max(last_frame_, now); }
  // Torn down (failed, unplugged or stalled): the next open is tried a reopen interval from `now`.
  void lost(Nanos now) {
    streaming_ = false;
    reopen_at_ = now + reopen_interval_;
  }

  // Streaming but no usable frame for the frame timeout: a wedged device, or one that vanished
  // without an error; it is torn down like a failed one.
  bool stalled(Nanos now) const { return streaming_ && now >= last_frame_ + frame_timeout_; }
  bool reopen_due(Nanos now) const { return !streaming_ && now >= reopen_at_; }
  // When the camera's timer must wake the loop: the stall deadline while streaming, else the reopen.
  Nanos deadline() const { return streaming_ ? last_frame_ + frame_timeout_ : reopen_at_; }
  Nanos last_frame() const { return last_frame_; }

 private:
  Nanos reopen_interval_;
  Nanos frame_timeout_;
  bool streaming_ = false;
  Nanos last_frame_{0};
  Nanos reopen_at_{0};
};

}  // namespace hal::detail
