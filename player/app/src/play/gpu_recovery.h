#pragma once
// Recovery from a GPU reset. After a reset every GL resource is gone, so a play session cannot mend
// itself: its loop returns kRemake, and play_with_recovery() makes a new session (platform, context,
// programs, scenes) that plays on from where the last one was (the Resume). The kms platform asks
// for the same when it can only have its display again through a new open of the device.
#include "hal/clock.h"
#include "play/play_clock.h"

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>

namespace app {

class StatusReporter;

// A session's answer when the platform must be made anew.
constexpr int kRemake = -1;
// The process's code when the context is lost and cannot be rebuilt here (no reset notification,
// or resets that keep coming): a service manager restarts the player.
constexpr int kGpuLost = 4;

// Where a session that lost its GPU context was: the next one plays on from there.
struct Resume {
  bool resumed = false;
  PlayClock::Steady::time_point start = PlayClock::Steady::now();
  double wall_start = wall_seconds();
  hal::Nanos manual_now{0};
  long long frames = 0;
  std::uint64_t gpu_resets = 0;  // sessions made anew so far (the metrics count them)
};

// What a session's GL context says of itself.
class GpuWatch {
 public:
  // GL errors, looked for every status period rather than after each pass: glGetError costs a
  // round trip on some drivers. An error is reported; GL_CONTEXT_LOST is remembered.
  void look_for_errors(StatusReporter& status);
  // After a presented frame: why the context must be made anew (the GPU was reset: a query the
  // driver answers from the CPU side), or empty. `frame`: the frame just presented.
  std::string reset_reason(long long frame) const;
  // The context is lost and the driver does not tell of resets: nothing can be rebuilt here.
  bool lost_for_good() const { return context_lost_; }

 private:
  bool context_lost_ = false;
};

// A session: plays from `resume` and returns its exit code, or kRemake with where it was in `next`
// and why in `reason`.
using PlaySession = std::function<int(const Resume& resume, Resume& next, std::string& reason)>;
// Runs sessions until one returns an exit code; a GPU that resets more than three times within a
// minute is not recovering here, so that exits kGpuLost for a fresh process (or a reboot).
int play_with_recovery(const PlaySession& session, std::ostream& out, std::ostream& err);

}  // namespace app
