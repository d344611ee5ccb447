// The kms platform's start, its frames and its scanout capture; hotplug is in kms_hotplug.cpp.
#include "kms_platform.h"

#include "kms_writeback.h"

#include "base/errno_text.h"
#include "uevent.h"

#include <EGL/egl.h>
#include <poll.h>
#include <xf86drm.h>

#include <cerrno>
#include <utility>

namespace platform {
namespace kms {
namespace {

// The platform whose flips drmHandleEvent is delivering now, for on_flip.
thread_local KmsPlatform* handling_events = nullptr;

}  // namespace

KmsPlatform::~KmsPlatform() {
  // The locked buffers go back (with the surface) only once no flip still scans one out.
  settle_flip();
}

std::unique_ptr<Platform> KmsPlatform::create(const Options& options, std::string& error) {
  auto platform = std::unique_ptr<KmsPlatform>(new KmsPlatform());
  KmsPlatform& self = *platform;
  self.wanted_connector_ = options.drm_connector;
  if (!parse_mode_request(options.drm_mode, self.wanted_mode_, error)) return nullptr;
  if (options.drm_atomic != "auto" && options.drm_atomic != "no") {
    error = "--drm-atomic: expected auto or no, got '" + options.drm_atomic + "'";
    return nullptr;
  }
  std::string why;
  if (!open_device(options.drm_device, self.fd_, self.device_path_, why)) {
    error = "kms: " + why;
    return nullptr;
  }
  const int fd = self.fd_.get();
  if (auto* version = drmGetVersion(fd)) {
    self.driver_ = version->name;
    drmFreeVersion(version);
  }
  // The one place atomic and legacy part: from here on the platform holds a Commit.
  self.commit_ = enable_client_caps(fd, options.drm_atomic == "auto") ? make_atomic_commit(fd) : make_legacy_commit(fd);
  self.surface_ = Surface::create(fd, self.device_path_, options.debug_context, error);
  if (!self.surface_) return nullptr;

  Probe found;
  if (!probe(fd, found, why)) {
    error = "kms: " + self.device_path_ + ": " + why;
    return nullptr;
  }
  self.writeback_ = found.writeback;
  const Choice choice = choose_output(found.connectors, self.wanted_connector_, self.wanted_mode_);
  if (choice.outcome == Choice::Outcome::no_such_connector || choice.outcome == Choice::Outcome::no_such_mode) {
    error = "kms: " + choice.why + "\n" + describe_connectors(self.device_path_, found.connectors);
    return nullptr;
  }
  const bool chosen = choice.outcome == Choice::Outcome::chosen;
  // Without a display the context still needs a surface to be current on; it is replaced by one of
  // the mode's size when a display comes.
  const Mode* mode =
      chosen ? &found.connectors[static_cast<size_t>(choice.connector)].modes[static_cast<size_t>(choice.mode)] : nullptr;
  if (!self.make_surface(mode != nullptr ? Size{mode->width, mode->height} : options.size, error)) return nullptr;
  if (chosen) {
    if (!self.set_up_output(found, choice, error)) return nullptr;
    self.presenting_ = true;
  } else {
    self.reason_ = choice.why;
  }
  self.uevent_fd_.reset(uevent::open_socket());
  if (!self.uevent_fd_)
    self.warn("kms: no hotplug events (netlink uevent socket: " + base::errno_text(errno) +
              "); displays are looked for every second");
  return platform;
}

std::string KmsPlatform::description() const {
  std::string text = "DRM/KMS on " + device_path_ + " (" + driver_ + "), " + std::string(commit_->kind().modesetting) +
                     " modesetting, " + surface_->format_name();
  if (presenting_)
    text += ", " + connector_.name + " " + describe(mode_);
  else
    text += ", " + reason_;
  return text;
}

void* KmsPlatform::proc_address(const char* name) const {
  return reinterpret_cast<void*>(eglGetProcAddress(name));
}

bool KmsPlatform::resize(Size size, std::string& error) {
  const Size current = surface_->size();
  if (size == current) return true;
  error = "kms: the surface is the display mode's size (" + std::to_string(current.width) + "x" + std::to_string(current.height) +
          "); --drm-mode chooses another";
  return false;
}

bool KmsPlatform::make_surface(Size size, std::string& error) {
  settle_flip();
  if (!surface_->resize(size, error)) return false;
  needs_modeset_ = true;
  return true;
}

bool KmsPlatform::set_up_output(const Probe& found, const Choice& choice, std::string& error) {
  const auto index = static_cast<size_t>(choice.connector);
  const Connector& connector = found.connectors[index];
  Target target;
  target.connector = connector.id;
  target.mode = found.raw_modes[index][static_cast<size_t>(choice.mode)];
  if (!find_crtc(fd_.get(), connector.id, target.crtc, target.crtc_index)) {
    error = "kms: no CRTC can drive " + connector.name;
    return false;
  }
  Commit::Prepared prepared = commit_->prepare(target, error);
  if (prepared == Commit::Prepared::unsupported) {
    // A driver whose atomic interface lacks what a modeset needs: legacy does it, from now on.
    commit_ = make_legacy_commit(fd_.get(), commit_->driven_crtc());
    prepared = commit_->prepare(target, error);
  }
  if (prepared != Commit::Prepared::ready) return false;
  const Mode mode = connector.modes[static_cast<size_t>(choice.mode)];
  if (Size{mode.width, mode.height} != surface_->size()) {
    if (!make_surface({mode.width, mode.height}, error)) return false;
    push(EventType::resized);
  }
  connector_ = connector;
  mode_ = mode;
  target_ = target;
  needs_modeset_ = true;
  return true;
}

void KmsPlatform::on_flip(int fd, unsigned frame, unsigned sec, unsigned usec, void* data) {
  (void)fd;
  (void)frame;
  (void)sec;
  (void)usec;
  KmsPlatform* self = handling_events;
  if (self != nullptr && self->flip_pending_ && reinterpret_cast<std::uintptr_t>(data) == self->flip_sequence_) self->flip_done();
}

void KmsPlatform::flip_done() {
  flip_pending_ = false;
  flip_timeouts_ = 0;
  surface_->flip_completed();
}

void KmsPlatform::abandon_flip() {
  flip_pending_ = false;
  ++flip_sequence_;
}

bool KmsPlatform::wait_for_flip(int timeout_ms) {
  drmEventContext handlers{};
  handlers.version = 2;
  handlers.page_flip_handler = on_flip;
  const SteadyClock::time_point deadline = SteadyClock::now() + std::chrono::milliseconds(timeout_ms);
  handling_events = this;
  while (flip_pending_) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - SteadyClock::now()).count();
    if (left < 0) break;
    pollfd wait{fd_.get(), POLLIN, 0};
    const int ready = poll(&wait, 1, static_cast<int>(left));
    if (ready < 0 && errno != EINTR) break;
    if (ready > 0) drmHandleEvent(fd_.get(), &handlers);
  }
  handling_events = nullptr;
  return !flip_pending_;
}

bool KmsPlatform::set_display_power(bool on, std::string& state, std::string& error) {
  if (on == !powered_off_) {
    state = std::string("already ") + (on ? "on" : "off");
    return true;
  }
  powered_off_ = !on;
  // Without a display the change waits: off, nothing is set when one comes; on, the modeset that
  // a display's arrival makes anyway shows it.
  if (!presenting_ || !commit_) {
    state = "no display to switch (" + reason_ + ")";
    return true;
  }
  settle_flip();
  int code = 0;
  if (on) {
    // The next present() sets the mode, which switches the CRTC on (atomic: ACTIVE=1 in the same commit).
    needs_modeset_ = true;
    if (!commit_->power_on(code)) {
      error = "kms: switching " + connector_.name + " on (DPMS) failed (" + base::errno_text(code) + ")";
      return false;
    }
    state = connector_.name + ": on at the next frame's modeset";
    return true;
  }
  if (!commit_->power_off(code)) {
    powered_off_ = false;
    error = "kms: switching " + connector_.name + " off failed (" + base::errno_text(code) + ")";
    return false;
  }
  const std::optional<bool> powered = commit_->powered();
  // Read back from the kernel, not taken from the commit's success.
  const bool atomic = commit_->kind().modesetting == "atomic";
  state = connector_.name + (atomic ? " CRTC " + std::to_string(target_.crtc) + " ACTIVE=" : " DPMS=") +
          (!powered ? std::string("unreadable")
           : atomic ? (*powered ? "1" : "0")
                    : (*powered ? "on" : "off"));
  return true;
}

void KmsPlatform::settle_flip() {
  if (flip_pending_ && !wait_for_flip(kFlipTimeoutMs)) abandon_flip();
}

bool KmsPlatform::present() {
  if (!presenting_ || powered_off_) return true;
  gbm_bo* bo = surface_->swap(last_error_);
  if (bo == nullptr) return false;
  std::string error;
  const std::uint32_t fb = surface_->framebuffer_for(bo, error);
  if (fb == 0) {
    surface_->release(bo);
    warn(error);
    stop_presenting("the display takes no framebuffer of this surface: " + error, true);
    return true;
  }
  // The previous frame's flip first: its completion frees the buffer shown before it, and is what
  // paces the loop to the display's refresh.
  if (flip_pending_ && !wait_for_flip(kFlipTimeoutMs)) {
    abandon_flip();
    needs_modeset_ = true;
    warn("kms: a page flip on " + connector_.name + " did not complete within " + std::to_string(kFlipTimeoutMs) +
         " ms; setting the mode again");
    if (++flip_timeouts_ >= kFlipTimeoutsBeforeGivingUp) {
      surface_->release(bo);
      last_error_ = "kms: " + std::to_string(kFlipTimeoutsBeforeGivingUp) + " page flips in a row on " + connector_.name + " (" +
                    device_path_ + ") did not complete within " + std::to_string(kFlipTimeoutMs) + " ms";
      return false;
    }
  }
  int code = 0;
  const bool setting_mode = needs_modeset_;
  if (setting_mode) {
    if (commit_->modeset(fb, code)) {
      needs_modeset_ = false;
      backoff_ = std::chrono::milliseconds(100);
      surface_->shown_by_modeset(bo);
      return true;
    }
  } else if (commit_->flip(fb, flip_sequence_, code)) {
    surface_->flip_queued(bo);
    flip_pending_ = true;
    return true;
  }
  surface_->release(bo);
  commit_failed(setting_mode, code);
  return true;
}

void KmsPlatform::commit_failed(bool setting_mode, int code) {
  if (code == EBUSY) return;  // the previous commit is still in flight: this frame is dropped
  needs_modeset_ = true;
  if (code == EACCES || code == EPERM) {
    // Another client (a VT switch, a display server) holds DRM master: wait for it to let go.
    stop_presenting("another process holds the display (DRM master)", true);
    return;
  }
  const Commit::Kind& kind = commit_->kind();
  const std::string what = std::string(setting_mode ? kind.modeset : kind.flip) + connector_.name + " " + describe(mode_) +
                           " failed (" + base::errno_text(code) + ")";
  warn("kms: " + what);
  stop_presenting(std::string(setting_mode ? "the display refused the mode: " : "the display refused a page flip: ") + what,
                  true);
}

bool KmsPlatform::capture_scanout(std::vector<std::uint8_t>& rgba, Size& size, std::string& error) {
  if (!commit_->kind().writeback) {
    error = "kms: capturing the scanout needs atomic modesetting (the driver lacks it, or --drm-atomic no)";
    return false;
  }
  if (writeback_ == 0) {
    error = "kms: " + device_path_ + " (" + driver_ + ") has no writeback connector to capture the scanout with";
    return false;
  }
  if (!presenting_ || !surface_->showing()) {
    error = "kms: nothing is shown to capture (" + (presenting_ ? std::string("no frame presented yet") : reason_) + ")";
    return false;
  }
  if (flip_pending_ && !wait_for_flip(kFlipTimeoutMs)) {
    error = "kms: the last page flip did not complete within " + std::to_string(kFlipTimeoutMs) + " ms";
    return false;
  }
  WritebackCapture capture;
  capture.fd = fd_.get();
  capture.writeback = writeback_;
  capture.crtc = target_.crtc;
  capture.display_connector = connector_.id;
  capture.display_connector_crtc = commit_->connector_crtc_property();
  capture.display_name = connector_.name;
  capture.width = mode_.width;
  capture.height = mode_.height;
  capture.timeout_ms = kFlipTimeoutMs * 5;
  const bool ok = capture_writeback(capture, rgba, error, needs_modeset_);
  if (ok) size = {mode_.width, mode_.height};
  return ok;
}

void KmsPlatform::push(EventType type) {
  if (queued_ == queue_.size()) return;  // a burst of hotplugs: the last state is what counts
  Event& event = queue_[queued_++];
  event = {};
  event.type = type;
  event.size = surface_->size();
}

void KmsPlatform::warn(std::string text) {
  if (text == last_error_) return;
  last_error_ = std::move(text);
  push(EventType::warning);
}

}  // namespace kms

std::unique_ptr<Platform> create_kms(const Options& options, std::string& error) {
  return kms::KmsPlatform::create(options, error);
}

}  // namespace platform
