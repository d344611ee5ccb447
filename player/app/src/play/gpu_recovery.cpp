#include "play/gpu_recovery.h"

#include "gl/gl_api.h"
#include "play/status_reporter.h"

#include <cstdio>
#include <ostream>
#include <vector>

namespace app {

void GpuWatch::look_for_errors(StatusReporter& status) {
  const GLenum gl_status = gl::api.GetError();
  if (gl_status == GL_CONTEXT_LOST_KHR) context_lost_ = true;
  if (gl_status != GL_NO_ERROR) {
    char text[64];
    std::snprintf(text, sizeof text, "GL error 0x%04x during playback", gl_status);
    status.report(ErrorKind::gpu, text);
  }
}

std::string GpuWatch::reset_reason(long long frame) const {
  if (gl::api.GetGraphicsResetStatus == nullptr) return {};
  const GLenum reset = gl::api.GetGraphicsResetStatus();
  if (reset == GL_NO_ERROR) return {};
  return std::string("the GPU was reset (") +
         (reset == GL_GUILTY_CONTEXT_RESET_KHR     ? "caused by this player"
          : reset == GL_INNOCENT_CONTEXT_RESET_KHR ? "caused elsewhere"
                                                   : "cause unknown") +
         ") at frame " + std::to_string(frame);
}

int play_with_recovery(const PlaySession& session, std::ostream& out, std::ostream& err) {
  using Steady = PlayClock::Steady;
  Resume resume;
  std::string reason;
  std::vector<Steady::time_point> resets;
  for (;;) {
    Resume next;
    // Every GL object, the context and the devices go before the next session opens them again.
    const int code = session(resume, next, reason);
    if (code != kRemake) return code;
    const Steady::time_point now = Steady::now();
    resets.push_back(now);
    std::erase_if(resets, [&](Steady::time_point t) { return now - t > std::chrono::minutes(1); });
    if (resets.size() > 3) {
      err << "error: the platform had to be made anew " << resets.size() << " times within a minute (last: " << reason
          << "); exiting (" << kGpuLost << ") for the service manager to restart the player\n";
      return kGpuLost;
    }
    next.gpu_resets = resume.gpu_resets + 1;
    resume = next;
    out << "remake: the platform, its context and every GL resource are made anew (" << reason << "); playing on from frame "
        << resume.frames << "\n"
        << std::flush;
  }
}

}  // namespace app
