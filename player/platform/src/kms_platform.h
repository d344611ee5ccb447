#pragma once
// The board platform: EGL on a GBM surface, shown through DRM/KMS without a display server, as
// kmscube and mpv's drm output do it. One connector and CRTC, the primary plane; atomic modesetting
// where the driver offers it, legacy SetCrtc/PageFlip otherwise. Frames are paced by the page-flip
// events; hotplug arrives as kernel uevents; losing DRM master (a VT switch, another client) stops
// the commits until master comes back.
//
// The parts, each in its own file: kms_device (finding the device, reading its connectors),
// kms_output (which connector and mode, on plain data), kms_commit with kms_atomic and kms_legacy
// (how a frame reaches the display), kms_surface (EGL on GBM), kms_writeback (reading back what is
// shown), kms_hotplug (uevents and retries: this class's drain_events).
#include "backends.h"
#include "kms_commit.h"
#include "kms_device.h"
#include "kms_output.h"
#include "kms_surface.h"

#include "base/unique_fd.h"

#include <array>
#include <chrono>
#include <memory>
#include <string>

namespace platform::kms {

class KmsPlatform final : public Platform {
 public:
  ~KmsPlatform() override;

  static std::unique_ptr<Platform> create(const Options& options, std::string& error);

  std::string_view name() const override { return "kms"; }
  std::string description() const override;
  std::vector<std::string> extensions_used() const override { return {surface_->extension()}; }
  void* proc_address(const char* name) const override;
  Size size() const override { return surface_->size(); }
  unsigned framebuffer() const override { return 0; }
  bool srgb_framebuffer() const override { return false; }
  bool resize(Size size, std::string& error) override;
  bool present() override;
  int event_fd() const override { return uevent_fd_.get(); }
  std::size_t drain_events(std::span<Event> out) override;
  bool presenting() const override { return presenting_; }
  std::string not_presenting_reason() const override { return presenting_ ? std::string() : reason_; }
  int poll_interval_ms() const override { return 100; }
  std::string last_error() const override { return last_error_; }
  bool capture_scanout(std::vector<std::uint8_t>& rgba, Size& size, std::string& error) override;
  bool set_display_power(bool on, std::string& state, std::string& error) override;

 private:
  using SteadyClock = std::chrono::steady_clock;
  // A flip that takes this long is not coming: the error path re-modesets. Far above any refresh
  // period, and above what a display under software emulation needs (about 10x slower than real time).
  static constexpr int kFlipTimeoutMs = 1000;
  static constexpr int kFlipTimeoutsBeforeGivingUp = 3;

  KmsPlatform() = default;

  // Each commit's event carries its sequence number as user data; an event of a flip given up on
  // (timed out, then completed late) must not be taken for the one pending now.
  static void on_flip(int fd, unsigned frame, unsigned sec, unsigned usec, void* data);
  void flip_done();
  // A flip that did not complete in time: its buffer stays locked (it may be on screen or become so)
  // until a modeset puts a new one there; its event, should it come, is ignored.
  void abandon_flip();
  bool wait_for_flip(int timeout_ms);
  void settle_flip();  // waits for a pending flip, giving it up after kFlipTimeoutMs
  bool make_surface(Size size, std::string& error);
  // Drives what `choice` chose (a CRTC, the commit's properties, a surface of the mode's size).
  bool set_up_output(const Probe& found, const Choice& choice, std::string& error);
  // The commit's error: the frame is dropped, or presenting stops until a retry or a hotplug.
  void commit_failed(bool setting_mode, int code);

  // kms_hotplug.cpp: reads the connectors and starts or stops presenting to match.
  void reprobe();
  bool uevents_changed();
  void retry(SteadyClock::time_point now, bool& changed);
  void stop_presenting(std::string reason, bool retry);
  // After an error that a new open of the device would clear: the player makes the platform anew.
  void request_remake(std::string reason);
  void push(EventType type);
  void warn(std::string text);

  base::UniqueFd fd_, uevent_fd_;
  std::string device_path_, driver_;
  std::unique_ptr<Commit> commit_;
  std::unique_ptr<Surface> surface_;
  std::uint32_t writeback_ = 0;

  // What is driven: the options that choose it, and what they chose.
  std::string wanted_connector_;
  ModeRequest wanted_mode_;
  Connector connector_;
  Mode mode_;
  Target target_;

  bool presenting_ = false, needs_modeset_ = true, flip_pending_ = false;
  bool powered_off_ = false;  // set_display_power(false): present() shows nothing until it is on
  std::uint64_t flip_sequence_ = 1;
  int flip_timeouts_ = 0;  // in a row: reset only when a flip's event arrives
  std::string reason_ = "no display", last_error_;
  // After an error (master lost, a refused modeset) the output is tried again at retry_at_, the
  // wait doubling up to 5 s; a uevent tries at once.
  bool retry_pending_ = false;
  SteadyClock::time_point retry_at_{};
  std::chrono::milliseconds backoff_{100};
  SteadyClock::time_point next_look_{};  // without hotplug events: when the connectors are read again

  std::array<Event, 16> queue_{};
  std::size_t queued_ = 0;
};

}  // namespace platform::kms
