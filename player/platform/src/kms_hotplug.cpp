// The kms platform between frames: kernel uevents say a connector changed (or, without them, the
// connectors are read every second), and the output is chosen again with the same rules as at the
// start (choose_output); after an error the output is tried again with a growing wait, and DRM
// master lost to another client is waited for.
#include "kms_platform.h"

#include "uevent.h"

#include <sys/socket.h>
#include <xf86drm.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace platform::kms {

void KmsPlatform::stop_presenting(std::string reason, bool retry) {
  settle_flip();
  reason_ = std::move(reason);
  retry_pending_ = retry;
  if (retry) retry_at_ = SteadyClock::now() + backoff_;
  if (presenting_) {
    presenting_ = false;
    push(EventType::display_lost);
  }
}

void KmsPlatform::request_remake(std::string reason) {
  reason_ = std::move(reason);
  last_error_ = reason_;
  push(EventType::remake);
}

void KmsPlatform::reprobe() {
  Probe found;
  std::string why;
  if (!probe(fd_.get(), found, why)) {
    stop_presenting(why, true);
    return;
  }
  writeback_ = found.writeback;
  const Choice choice = choose_output(found.connectors, wanted_connector_, wanted_mode_);
  switch (choice.outcome) {
    case Choice::Outcome::chosen:
      break;
    case Choice::Outcome::no_such_mode:
      warn("kms: " + choice.why);
      [[fallthrough]];
    case Choice::Outcome::waiting:
    case Choice::Outcome::no_such_connector:
      stop_presenting(choice.why, false);
      return;
  }
  const auto index = static_cast<size_t>(choice.connector);
  const drmModeModeInfo& raw = found.raw_modes[index][static_cast<size_t>(choice.mode)];
  if (presenting_ && found.connectors[index].id == connector_.id && std::memcmp(&raw, &target_.mode, sizeof raw) == 0) {
    // The same display and mode; a link the driver marks bad (a DP replug) still wants a modeset.
    if (property_value(fd_.get(), connector_.id, DRM_MODE_OBJECT_CONNECTOR, "link-status", DRM_MODE_LINK_STATUS_GOOD) ==
        DRM_MODE_LINK_STATUS_BAD)
      needs_modeset_ = true;
    return;
  }
  if (!set_up_output(found, choice, why)) {
    warn(why);
    stop_presenting(why, true);
    return;
  }
  presenting_ = true;
  retry_pending_ = false;
  push(EventType::display_found);
}

bool KmsPlatform::uevents_changed() {
  bool changed = false;
  char buffer[4096];
  for (;;) {
    const ssize_t length = recv(uevent_fd_.get(), buffer, sizeof buffer, MSG_DONTWAIT);
    if (length < 0 && errno == ENOBUFS) {
      changed = true;  // events were dropped: whatever they said, the connectors tell now
      continue;
    }
    if (length <= 0) break;
    uevent::Message message;
    if (uevent::parse({buffer, static_cast<size_t>(length)}, message) && uevent::is_drm_change_of(message, device_path_))
      changed = true;
  }
  return changed;
}

void KmsPlatform::retry(SteadyClock::time_point now, bool& changed) {
  if (reason_.find("DRM master") != std::string::npos && !drmIsMaster(fd_.get()) && drmSetMaster(fd_.get()) != 0) {
    // Without CAP_SYS_ADMIN the kernel gives master back only to a file that held it. Whether a
    // new open would get it says whether the other client is gone.
    base::UniqueFd probe_fd = open_node(device_path_);
    if (probe_fd && drmIsMaster(probe_fd.get())) {
      retry_pending_ = false;
      request_remake("kms: DRM master of " + device_path_ + " is free again, but only a new open of the device can have it");
    } else {
      backoff_ = std::min(backoff_ * 2, std::chrono::milliseconds(5000));
      retry_at_ = now + backoff_;
    }
  } else {
    changed = true;
    needs_modeset_ = true;
    backoff_ = std::min(backoff_ * 2, std::chrono::milliseconds(5000));
  }
}

std::size_t KmsPlatform::drain_events(std::span<Event> out) {
  bool changed = false;
  const SteadyClock::time_point now = SteadyClock::now();
  if (uevent_fd_) {
    changed = uevents_changed();
  } else if (now >= next_look_) {
    changed = true;  // no hotplug events: the connectors are read every second
    next_look_ = now + std::chrono::seconds(1);
  }
  if (!changed && retry_pending_ && now >= retry_at_) retry(now, changed);
  if (changed) {
    const bool was_presenting = presenting_;
    reprobe();
    if (presenting_ && !was_presenting) needs_modeset_ = true;
  }
  const std::size_t n = std::min(queued_, out.size());
  std::copy_n(queue_.begin(), n, out.begin());
  std::copy(queue_.begin() + static_cast<std::ptrdiff_t>(n), queue_.begin() + static_cast<std::ptrdiff_t>(queued_),
            queue_.begin());
  queued_ -= n;
  return n;
}

}  // namespace platform::kms
