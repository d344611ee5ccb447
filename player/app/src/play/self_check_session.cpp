#include "play/self_check_session.h"

#include "base/image_codec.h"

#include "gl/gl_api.h"
#include "hal/mock.h"
#include "play/kiosk_state.h"
#include "play/status_reporter.h"
#include "render/readback.h"

#include <algorithm>

namespace app {

SelfCheckSession::SelfCheckSession(hal::Camera* camera, hal::MockCamera* mock, std::vector<CameraStep> script, double interval_s,
                                   const hal::Clock& clock, StatusReporter& status, KioskState& kiosk)
    : camera_(camera),
      mock_(mock),
      script_(std::move(script)),
      interval_s_(interval_s),
      next_check_(interval_s > 0.0 ? interval_s : 0.0),
      clock_(clock),
      status_(status),
      kiosk_(kiosk) {}

void SelfCheckSession::start_when_due(double now, const render::PresentTarget& present, int width, int height) {
  if (requested_ && !checking_) start(now, present, width, height);
  if (interval_s_ > 0.0 && now >= next_check_ && !checking_) {
    next_check_ = now + interval_s_;
    start(now, present, width, height);
  }
}

void SelfCheckSession::start(double now, const render::PresentTarget& present, int w, int h) {
  requested_ = false;
  if (camera_ == nullptr) {
    status_.report(ErrorKind::self_check, "self-check: the board has no camera");
    return;
  }
  const std::vector<uint8_t> rgba = render::read_presented(present, w, h);
  image_.resize(w, h);
  for (size_t i = 0, n = static_cast<size_t>(w) * static_cast<size_t>(h); i < n; ++i)
    std::copy_n(&rgba[i * 4], 3, &image_.pixels[i * 3]);
  layout_ = hal::FiducialLayout::for_display(w, h, ++sequence_);
  hal::draw_fiducials(image_, layout_);
  // Bottom row first, as GL stores textures; in the target's encoding, so the blit copies the bytes as they are.
  std::vector<uint8_t> flipped(static_cast<size_t>(w) * static_cast<size_t>(h) * 4, 255);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      std::copy_n(image_.at(x, h - 1 - y), 3,
                  &flipped[(static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 4]);
  frame_ = make_blit_source(w, h, present.srgb);
  gl::api.BindTexture(GL_TEXTURE_2D, frame_.texture.id());
  gl::api.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl::api.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, flipped.data());
  started_ = now;
  checking_ = true;
  if (mock_ != nullptr) mock_->show(image_);
}

void SelfCheckSession::draw(const render::PresentTarget& present, int w, int h) const {
  gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, frame_.framebuffer.id());
  gl::api.BindFramebuffer(GL_DRAW_FRAMEBUFFER, present.framebuffer);
  gl::api.BlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

bool SelfCheckSession::service_camera(double now) {
  if (camera_ == nullptr) return false;
  while (next_step_ < script_.size() && script_[next_step_].at_s <= now) {
    if (script_[next_step_++].plugged)
      mock_->replug();
    else
      mock_->unplug();
  }
  // The queue is drained before the stall check: after a long frame (shader compilation at start,
  // a slow board) a frame waiting there is not a stalled camera.
  const bool drained = !checking_ && camera_->read_frame(capture_);
  camera_->service();
  bool status_due = false;
  const bool lost = camera_->state() != hal::CameraState::streaming;
  if (lost != camera_lost_) {
    if (lost) status_.report(ErrorKind::device, "camera: " + camera_->last_error());
    camera_lost_ = lost;
    status_due = true;
  }
  if (!checking_) {
    if (!drained) camera_->read_frame(capture_);  // keep the queue drained between checks
    return status_due;
  }
  return verdict(now) || status_due;
}

bool SelfCheckSession::write_camera_frame(const std::string& path, std::string& error) const {
  if (camera_ == nullptr) {
    error = "the board has no camera";
    return false;
  }
  if (camera_lost_ || capture_.empty()) {
    error = camera_lost_ ? "the camera is lost (" + camera_->last_error() + ")" : "the camera has delivered no frame yet";
    return false;
  }
  base::images::WriteSpec spec;
  spec.width = capture_.width;
  spec.height = capture_.height;
  spec.channels = 3;
  if (base::images::write(path, spec, capture_.pixels.data(), error) != base::images::WriteFailure::none) {
    error = path + ": " + error;
    return false;
  }
  return true;
}

bool SelfCheckSession::verdict(double now) {
  constexpr double kCheckTimeout = 3.0;
  if (camera_->read_frame(capture_)) {
    const hal::SelfCheckResult result = checker_.check(image_, layout_, capture_);
    last_ = hal::CheckSummary{result.passed, result.score, result.reason, clock_.now()};
    if (!result.passed) status_.report(ErrorKind::self_check, "self-check failed: " + result.reason);
    checking_ = false;
  } else if (now - started_ > kCheckTimeout) {
    last_ = hal::CheckSummary{false, 0.0, "no camera frame within 3 s", clock_.now()};
    status_.report(ErrorKind::self_check, "self-check failed: no camera frame within 3 s");
    checking_ = false;
  }
  if (checking_) return false;
  kiosk_.check_finished(last_->passed);
  if (mock_ != nullptr) mock_->show(image_);  // the synthetic camera films the last frame shown
  return true;
}

void SelfCheckSession::append_warnings(std::vector<std::string>& out) const {
  if (camera_lost_) out.push_back("camera: " + camera_->last_error());
}

}  // namespace app
