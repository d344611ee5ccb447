#pragma once
// The display self-check and the camera it needs. A check holds one frame with AprilTag markers in
// the corners on screen until the camera delivers a capture of it (or a timeout), then compares
// them (hal::DisplayChecker); the playlist clock runs on meanwhile. Between checks the camera's
// queue is kept drained and its state watched: a lost camera is a warning until it is back.
#include "blit_source.h"
#include "camera_script.h"
#include "hal/camera.h"
#include "hal/clock.h"
#include "hal/image.h"
#include "hal/self_check.h"
#include "hal/status.h"
#include "render/passes.h"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace hal {
class MockCamera;
}

namespace app {

class KioskState;
class StatusReporter;

class SelfCheckSession {
 public:
  // `camera`: null when the board has none. `mock`: the mock backend's camera (null otherwise),
  // which films what it is shown and follows `script` (--camera-script). `interval_s`: a check every
  // so often (0: only when asked). `clock`: the devices' clock, which dates the verdicts.
  SelfCheckSession(hal::Camera* camera, hal::MockCamera* mock, std::vector<CameraStep> script, double interval_s,
                   const hal::Clock& clock, StatusReporter& status, KioskState& kiosk);

  // A check asked for (SIGUSR1, the check button): it starts with the next frame.
  void request() { requested_ = true; }
  bool has_camera() const { return camera_ != nullptr; }
  // Starts a check when one was asked for or the interval is up, from the frame last drawn into
  // `present` (width x height): that frame with the markers is what the screen holds.
  void start_when_due(double now, const render::PresentTarget& present, int width, int height);
  bool checking() const { return checking_; }
  // Draws the held check frame into `present`.
  void draw(const render::PresentTarget& present, int width, int height) const;
  // The camera's turn, every loop: the script's plugs, the queue, the lost state, the verdict of a
  // running check. True when the status must go out now (the camera came or went, a verdict).
  bool service_camera(double now);

  bool camera_lost() const { return camera_lost_; }
  // The camera lost, for the status file's warnings.
  void append_warnings(std::vector<std::string>& out) const;
  const std::optional<hal::CheckSummary>& last_verdict() const { return last_; }
  // The camera's latest frame (kept drained between checks) to an image file: what the screen looks
  // like from the camera, beside a screenshot. False and why (no camera, lost, nothing captured yet).
  bool write_camera_frame(const std::string& path, std::string& error) const;

 private:
  void start(double now, const render::PresentTarget& present, int width, int height);
  bool verdict(double now);

  hal::Camera* camera_;
  hal::MockCamera* mock_;
  std::vector<CameraStep> script_;
  size_t next_step_ = 0;
  double interval_s_, next_check_ = 0.0;
  const hal::Clock& clock_;
  StatusReporter& status_;
  KioskState& kiosk_;

  bool requested_ = false, checking_ = false, camera_lost_ = false;
  double started_ = 0.0;
  std::uint32_t sequence_ = 0;
  hal::DisplayChecker checker_;
  hal::FiducialLayout layout_;
  hal::RgbImage image_, capture_;
  BlitSource frame_;  // the check frame, held on screen while the check runs
  std::optional<hal::CheckSummary> last_;
};

}  // namespace app
