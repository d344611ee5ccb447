#include "play/play_loop.h"

#include "base/image_codec.h"
#include "image_io.h"
#include "shader_cache.h"

#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <ostream>
#include <set>
#include <sstream>

namespace app {
namespace {

namespace fs = std::filesystem;

// Milliseconds since the process started (kernel start time, 10 ms resolution).
double ms_since_process_start() {
  std::ifstream stat("/proc/self/stat");
  std::string text((std::istreambuf_iterator<char>(stat)), std::istreambuf_iterator<char>());
  const size_t close = text.rfind(')');
  if (close == std::string::npos) return -1.0;
  std::istringstream fields(text.substr(close + 2));
  std::string field;
  for (int i = 3; i < 22 && fields >> field; ++i) {
  }
  unsigned long long start_ticks = 0;
  if (!(fields >> start_ticks)) return -1.0;
  timespec boot{};
  clock_gettime(CLOCK_BOOTTIME, &boot);
  const double now_s = static_cast<double>(boot.tv_sec) + static_cast<double>(boot.tv_nsec) * 1e-9;
  return (now_s - static_cast<double>(start_ticks) / static_cast<double>(sysconf(_SC_CLK_TCK))) * 1000.0;
}

}  // namespace

PlayLoop::PlayLoop(const PlayPieces& pieces, std::string playlist_path, std::shared_ptr<const playback::Playlist> playlist,
                   long long frames)
    : p_(pieces),
      playlist_path_(std::move(playlist_path)),
      playlist_(std::move(playlist)),
      schedule_(pieces.opening_hours),
      frame_(frames),
      scene_shown_(frames > 0) {
  if (!playlist_path_.empty() && !p_.options.inputs.empty())
    bundle_.open(fs::absolute(p_.options.inputs.front()).lexically_normal().string());
}

void PlayLoop::update_status(bool force) {
  p_.status.announce_state();  // before the period: a state change reaches systemd at once
  if (!p_.status.due(force)) return;
  gpu_.look_for_errors(p_.status);
  hal::StatusReport report;
  if (timeline_ && last_item_ >= 0) report.item = playlist_->items[static_cast<size_t>(last_item_)].scene;
  report.frames = static_cast<std::uint64_t>(frame_);
  report.warnings = p_.devices.problems;  // devices missing since start: the player goes on without them
  p_.check.append_warnings(report.warnings);
  p_.scenes.append_warnings(report.warnings);
  report.self_check = p_.check.last_verdict();
  p_.status.publish(std::move(report), timeline_ ? last_item_ : -1);
}

void PlayLoop::watch_content() {
  std::set<std::string> folders;
  if (!playlist_path_.empty()) folders.insert(fs::path(playlist_path_).parent_path().string());
  if (bundle_.active()) folders.insert(bundle_.folder());  // the swap of its `current`, and refused installs
  for (const playback::Item& item : playlist_->items) {
    if (item.scene.rfind("builtin:", 0) != 0) folders.insert(fs::path(item.scene).parent_path().string());
    if (!item.display.empty()) folders.insert(fs::path(item.display).parent_path().string());
    if (!item.environment.empty() && item.environment.rfind("builtin:", 0) != 0)
      folders.insert(fs::path(item.environment).parent_path().string());
  }
  std::vector<std::string> problems;
  p_.watch.watch(folders, problems);
  for (const std::string& problem : problems) p_.status.report(ErrorKind::content, problem);
}

void PlayLoop::apply_playlist(std::shared_ptr<const playback::Playlist> playlist, double now) {
  playlist_ = std::move(playlist);
  timeline_->replace(*playlist_, now);
  p_.scenes.set_playlist(*playlist_, timeline_.get());
  p_.drawer.configure_again();
  watch_content();
}

void PlayLoop::drain_content() {
  changes_.clear();
  p_.watch.drain(changes_);
  for (const ContentWatch::Change& change : changes_) {
    if (const BundleFollower::Event event = bundle_.event_of(change.path); event == BundleFollower::Event::swapped) {
      if (const std::string next = bundle_.swapped(); !next.empty()) {
        p_.out << "content: " << change.path << " now leads to " << next << "; loading it to show at the next item\n"
               << std::flush;
        p_.loader.load_playlist(next);
      }
    } else if (event == BundleFollower::Event::record) {
      if (const std::string refused = bundle_.refused_install(); !refused.empty())
        p_.status.report(ErrorKind::content, refused + " (the installed version keeps playing)");
    } else if (change.path != playlist_path_) {
      p_.scenes.reload(change.path);
    } else if (change.deleted) {
      p_.status.report(ErrorKind::content, change.path + ": the playlist was deleted (the last good one keeps playing)");
    } else {
      p_.loader.load_playlist(change.path);
    }
  }
}

void PlayLoop::drain_loader() {
  Loader::Result result;
  while (p_.loader.take(result)) {
    if (result.kind == Loader::Result::Kind::scene) {
      p_.scenes.take(result, *timeline_);
    } else if (bundle_.expects(result.path)) {
      if (result.error.empty()) {
        bundle_.hold(result.playlist, last_sequence_);
      } else {
        bundle_.drop();
        p_.status.report(ErrorKind::content, result.error + " (the playing version stays)");
      }
    } else if (!result.error.empty()) {
      p_.status.report(ErrorKind::content, result.error + " (the last good playlist keeps playing)");
    } else {
      // Scenes it names anew load when their items come up; changed scene files come through inotify.
      apply_playlist(result.playlist, p_.clock.now());
    }
  }
}

PlayLoop::Next PlayLoop::drain_platform(bool& closed) {
  std::array<platform::Event, 16> events;
  const size_t n = p_.platform.drain_events(events);
  for (size_t i = 0; i < n; ++i) {
    const platform::Event& event = events[i];
    switch (event.type) {
      case platform::EventType::close_requested:
        closed = true;
        break;
      case platform::EventType::resized: {
        std::string error;
        if (!p_.drawer.resized(error)) p_.status.report(ErrorKind::display, error);
        break;
      }
      case platform::EventType::display_lost:
        p_.out << "display: " << p_.platform.not_presenting_reason() << " at " << p_.clock.now()
               << " s; the playlist plays on unseen\n"
               << std::flush;
        p_.status.set_display_connected(false);
        if (schedule_.on()) p_.kiosk.display_lost();  // closed stays closed: the display was to be off anyway
        update_status(true);
        break;
      case platform::EventType::display_found:
        p_.status.set_display_connected(true);
        p_.out << "display: " << p_.platform.description() << " at " << p_.clock.now() << " s\n" << std::flush;
        display_found_s_ = p_.clock.now();
        p_.drawer.configure_again();
        break;
      case platform::EventType::warning:
        p_.status.report(ErrorKind::display, p_.platform.last_error());
        break;
      case platform::EventType::remake:
        remake_reason_ = p_.platform.last_error();
        break;
      case platform::EventType::key_press:
      case platform::EventType::key_release:
        p_.buttons.key(event.key, event.type == platform::EventType::key_press);
        break;
    }
  }
  return remake_reason_.empty() ? Next::go_on : Next::remake;
}

PlayLoop::Next PlayLoop::drain_events(bool& closed) {
  const SignalSource::Received signals = p_.signals.drain();
  for (int i = 0; i < signals.reloads; ++i) reload_everything();  // SIGHUP
  if (signals.check) p_.check.request();
  if (signals.stop) return Next::stop;
  drain_content();
  drain_loader();
  return drain_platform(closed);
}

void PlayLoop::act(hal::Action action, double now) {
  p_.status.note_action(action);
  switch (action) {
    case hal::Action::none:
      break;
    case hal::Action::next:
      timeline_->next(now);
      break;
    case hal::Action::previous:
      timeline_->previous(now);
      break;
    case hal::Action::restart:
      timeline_->restart(now);
      break;
    case hal::Action::pause:
      if (timeline_->paused())
        timeline_->resume(now);
      else
        timeline_->pause(now);
      break;
    case hal::Action::ao:
      p_.drawer.toggle_ao(p_.options.settings.ao);
      break;
    case hal::Action::output:
      p_.drawer.next_output();
      break;
    case hal::Action::check:
      p_.check.request();
      break;
  }
}

std::string PlayLoop::command(const control::Command& command, double now) {
  using control::Verb;
  switch (command.verb) {
    case Verb::next:
      act(hal::Action::next, now);
      return "ok: next";
    case Verb::previous:
      act(hal::Action::previous, now);
      return "ok: previous";
    case Verb::restart:
      act(hal::Action::restart, now);
      return "ok: restart";
    case Verb::check:
      act(hal::Action::check, now);
      return "ok: a display self-check is asked for";
    case Verb::pause:
      if (timeline_->paused()) return "ok: paused already";
      act(hal::Action::pause, now);
      return "ok: paused";
    case Verb::resume:
      if (!timeline_->paused()) return "ok: playing already";
      p_.status.note_action("resume");
      timeline_->resume(now);
      return "ok: playing";
    case Verb::reload:
      p_.status.note_action("reload");
      reload_everything();
      return playlist_path_.empty() ? "ok: reloading every scene" : "ok: reloading the playlist and every scene";
    case Verb::item: {
      const auto count = static_cast<int>(timeline_->playlist().items.size());
      if (command.item >= count)
        return "error: item " + std::to_string(command.item) + ": the playlist has " +
               (count == 1 ? std::string("one item, 0") : std::to_string(count) + " items, 0 to " + std::to_string(count - 1));
      if (!timeline_->show_item(command.item, now))
        return "error: item " + std::to_string(command.item) + ": its scene cannot be shown (see the status file's errors)";
      p_.status.note_action("item:" + std::to_string(command.item));
      return "ok: item " + std::to_string(command.item);
    }
    case Verb::screenshot:
      if (!schedule_.on()) return "error: the display is off (" + schedule_.describe() + "): no frame is drawn";
      screenshot_wanted_ = true;
      return {};  // answered once the next frame is drawn (show_frame)
    case Verb::display: {
      p_.status.note_action(command.display_on ? "display:on" : "display:off");
      std::string reply = schedule_.command(command.display_on);
      follow_schedule(now);
      return reply;
    }
  }
  return "error: unknown command";
}

void PlayLoop::reload_everything() {
  if (!playlist_path_.empty()) p_.loader.load_playlist(playlist_path_);
  p_.scenes.reload_all();
}

void PlayLoop::serve_control(double now) {
  // Only when a connection came or one is still to be answered: no system call in an idle frame.
  if (!p_.control.has_connections() &&
      std::none_of(control_fds_.begin(), control_fds_.end(), [&](int fd) { return poll_.readable(fd); }))
    return;
  p_.control.serve(
      p_.clock.real_seconds(),
      [&](const control::Command& c, const control::Server::Peer& peer) {
        std::string reply = command(c, now);
        p_.out << "control: " << control::format_command(c) << " from pid " << peer.pid << " (uid " << peer.uid << "): " << reply
               << "\n"
               << std::flush;
        return reply;
      },
      [&](const std::string& line) { p_.out << line << "\n"
                                            << std::flush; });
}

void PlayLoop::load_for(const playback::Cue& cue) {
  p_.scenes.request(cue);
  if (p_.scenes.step_uploads(p_.drawer.shown_key())) p_.drawer.configure_again();
}

// No display to show on (kms: none connected, or another process holds it): the playlist clock
// runs on and scenes keep loading, so a display that comes back shows the right item.
void PlayLoop::play_unseen(double now) {
  if (p_.kiosk.display_lost()) update_status(true);
  const playback::Cue cue = timeline_->at(now, p_.clock.wall_start() + now);
  last_item_ = cue.item;
  load_for(cue);
  if (p_.check.service_camera(now)) update_status(true);
  // The loop is alive and waiting, which is all the watchdog checks; READY=1 too, so a player
  // behind a switched-off TV starts as a service instead of timing out.
  p_.status.service().frame_presented(p_.clock.monotonic());
  update_status(false);
}

void PlayLoop::follow_schedule(double now) {
  if (!schedule_.update(p_.clock.wall_start() + now, p_.clock.real_seconds())) return;
  const bool on = schedule_.on();
  std::string state, error;
  if (!p_.platform.set_display_power(on, state, error)) p_.status.report(ErrorKind::display, error);
  p_.out << "schedule: " << schedule_.describe() << "; display " << (on ? "on" : "off") << " (" << state << ") at " << now
         << " s\n"
         << std::flush;
  p_.status.set_open(on);
  const bool opening = on && closed_;
  closed_ = !on;
  if (!on) {
    screenshot_wanted_ = false;
    if (p_.control.answers_pending()) p_.control.answer_later("error: the display was switched off before a frame was drawn");
    p_.kiosk.closed();
  } else if (opening && p_.check.has_camera()) {
    // What a display that slept all night shows is checked once it shows frames again. (Without a
    // display, the loop's next pass says no display, as for any pass.)
    p_.check.request();
  }
  update_status(true);
}

void PlayLoop::stay_closed(double now) {
  const playback::Cue cue = timeline_->at(now, p_.clock.wall_start() + now);
  last_item_ = cue.item;
  load_for(cue);
  // Alive and waiting, which is all the watchdog checks: a kiosk closed at start still starts.
  p_.status.service().frame_presented(p_.clock.monotonic());
  update_status(false);
}

playback::Cue PlayLoop::cue_at(double now) {
  playback::Cue cue = timeline_->at(now, p_.clock.wall_start() + now);
  // A new bundle version is shown from the first item that starts after it was loaded.
  if (std::shared_ptr<const playback::Playlist> next = bundle_.take_at(cue.sequence)) {
    p_.out << "content: playing " << bundle_.playing() << " from frame " << frame_ << "\n" << std::flush;
    playlist_path_ = bundle_.playing();
    apply_playlist(std::move(next), now);
    cue = timeline_->at(now, p_.clock.wall_start() + now);
  }
  last_sequence_ = cue.sequence;
  load_for(cue);
  // A reproducible run waits for the item's scene instead of showing frames of "loading".
  while (p_.clock.manual() && cue.item >= 0 && !p_.scenes.settled(cue.item)) {
    PollSet::wait_one(p_.loader.fd(), 100);
    drain_loader();
    cue = timeline_->at(now, p_.clock.wall_start() + now);
    load_for(cue);
  }
  return cue;
}

void PlayLoop::draw(const playback::Cue& cue) {
  KioskState::Shown shown = KioskState::Shown::nothing_playable;
  p_.drawer.prepare_nothing();
  if (cue.item >= 0) {
    const CachedScene* scene = p_.scenes.ready(cue.item);
    shown = scene != nullptr ? KioskState::Shown::scene : KioskState::Shown::loading;
    if (scene != nullptr) {
      p_.scenes.pose(cue.item, cue.item_time);
      p_.drawer.prepare(cue, p_.scenes.key_of(cue.item), *scene, playlist_->items[static_cast<size_t>(cue.item)], p_.status);
    }
  }
  if (p_.kiosk.frame_drawn(shown, timeline_->paused())) update_status(true);  // sets the LEDs too

  p_.drawer.begin_frame();
  drew_scene_ = shown == KioskState::Shown::scene && !p_.check.checking();
  if (p_.check.checking())
    p_.check.draw(p_.drawer.present(), p_.drawer.width(), p_.drawer.height());
  else
    p_.drawer.draw(cue.fade);
  p_.drawer.end_frame(!p_.check.checking(), p_.status);
  p_.drawer.draw_overlay(p_.kiosk.name(), *p_.devices.status);
}

void PlayLoop::wait_for_events(double next_frame) {
  // It sleeps only until the next frame is due.
  int timeout_ms = 0;
  if (!schedule_.on())
    timeout_ms = p_.clock.manual() ? 0 : kClosedPollMs;
  else if (!p_.platform.presenting())
    timeout_ms = p_.platform.poll_interval_ms();
  else if (!p_.clock.manual() && p_.options.fps > 0.0)
    timeout_ms = std::max(0, static_cast<int>((next_frame - p_.clock.now()) * 1000.0));
  control_fds_.clear();
  p_.control.fds(control_fds_);
  poll_.wait({p_.signals.fd(), p_.watch.fd(), p_.loader.fd(), p_.platform.event_fd(), p_.devices.buttons->fd(),
              p_.devices.status->fd(), p_.devices.camera ? p_.devices.camera->fd() : -1},
             control_fds_, timeout_ms);
}

void PlayLoop::read_buttons(double now) {
  actions_.clear();
  p_.buttons.read(*p_.devices.buttons, actions_);
  for (hal::Action action : actions_) act(action, now);
  if (!p_.devices.buttons->last_error().empty()) p_.status.report(ErrorKind::device, p_.devices.buttons->last_error());
}

std::optional<int> PlayLoop::show_frame(double now, double frame_interval, bool& stop, int& exit_code) {
  p_.check.start_when_due(now, p_.drawer.present(), p_.drawer.width(), p_.drawer.height());
  const playback::Cue cue = cue_at(now);
  last_item_ = cue.item;
  draw(cue);
  std::string error;
  if (!p_.options.out_dir.empty()) {
    char name[32];
    std::snprintf(name, sizeof name, "frame-%06lld.png", frame_);
    if (!p_.drawer.write_frame((fs::path(p_.options.out_dir) / name).string(), error)) {
      p_.err << "error: " << error << "\n";
      return 1;
    }
  }
  p_.drawer.finish();
  if (screenshot_wanted_) {
    // Read back on request only: it waits for the GPU, which no ordinary frame does.
    screenshot_wanted_ = false;
    const std::string path = (fs::path(p_.control.path()).parent_path() / "screenshot.png").string();
    const bool written = p_.drawer.write_surface(path, error);
    p_.status.note_action("screenshot");
    std::string reply = written ? "ok: frame " + std::to_string(frame_) + " written to " + path : "error: " + error;
    // What the check camera sees of the screen too, where the board has one.
    const std::string camera_path = (fs::path(path).parent_path() / "camera.png").string();
    if (written && p_.check.has_camera())
      reply +=
          p_.check.write_camera_frame(camera_path, error) ? "; camera frame written to " + camera_path : "; camera: " + error;
    p_.control.answer_later(reply);
    error.clear();
  }
  // The last frame as the GPU drew it onto the surface, before it goes to the display.
  if (!p_.options.snapshot.empty() && frame_ + 1 == p_.options.frames && !p_.drawer.write_surface(p_.options.snapshot, error)) {
    p_.err << "error: --snapshot: " << error << "\n";
    return 1;
  }
  if (!p_.platform.present()) {
    p_.err << "error: " << p_.platform.last_error() << "\n";
    exit_code = 3;
    stop = true;
  } else {
    p_.status.service().frame_presented(p_.clock.monotonic());  // only presented frames feed the watchdog
  }
  // A camera's MJPEG frames are decoded on this thread: the image module is loaded beside it, once the
  // first frame is shown, so that neither the start nor the first self-check waits for it.
  if (frame_ == 0 && p_.devices.camera && !p_.devices.mock_camera)
    image_preload_ = std::jthread([] {
      std::string ignored;  // the first use reports it, with the frame that needed it
      base::images::preload(ignored);
    });
  if (frame_ == 0)
    p_.out << "first frame presented " << ms_since_process_start()
           << " ms after the process started; shaders: " << program_counts(p_.drawer.programs()) << "\n"
           << std::flush;
  // What a restart costs the people in front of the screen: the first frame may be the loading screen.
  if (drew_scene_ && !scene_shown_) {
    scene_shown_ = true;
    p_.out << "first scene frame presented " << ms_since_process_start()
           << " ms after the process started; environments: " << environment_counts() << "\n"
           << std::flush;
  }
  if (display_found_s_ >= 0.0 && p_.platform.presenting()) {
    p_.out << "display: showing frames again " << (p_.clock.now() - display_found_s_) * 1000.0 << " ms after it came\n"
           << std::flush;
    display_found_s_ = -1.0;
  }
  if (p_.check.service_camera(now)) update_status(true);
  p_.status.frame_presented({frame_, now, cue.item, p_.check.camera_lost(), p_.scenes.swaps()});
  ++frame_;
  update_status(false);
  p_.clock.advance(frame_interval);
  if (p_.options.frames > 0 && frame_ >= p_.options.frames) {
    stop = true;
    return std::nullopt;
  }
  // After a reset every draw is dropped until the context is made anew.
  remake_reason_ = gpu_.reset_reason(frame_ - 1);
  if (!remake_reason_.empty()) {
    p_.err << "warning: " << remake_reason_ << "\n";
    return kRemake;
  }
  if (gpu_.lost_for_good()) {
    p_.err << "error: the GL context is lost and this driver does not tell of GPU resets, so nothing can be rebuilt; exiting ("
           << kGpuLost << ") for the service manager to restart the player\n";
    return kGpuLost;
  }
  stop = stop || cue.finished;
  return std::nullopt;
}

int PlayLoop::run() {
  p_.scenes.set_playlist(*playlist_, nullptr);
  timeline_ = std::make_unique<playback::Timeline>(*playlist_, 0.0, p_.clock.wall_start());
  watch_content();
  p_.status.set_display_connected(p_.platform.presenting());
  update_status(true);

  bool stop = false;
  int exit_code = 0;
  const double frame_interval = p_.options.fps > 0.0 ? 1.0 / p_.options.fps : 1.0 / 30.0;
  double next_frame = 0.0;
  while (!stop) {
    wait_for_events(next_frame);
    const Next next = drain_events(stop);
    if (next == Next::stop) break;
    if (next == Next::remake) return kRemake;
    const double now = p_.clock.now();
    read_buttons(now);
    serve_control(now);
    p_.devices.status->update();
    follow_schedule(now);
    if (!schedule_.on()) {
      stay_closed(now);
      // A reproducible run (a preview of the hours) passes the night in steps of a second, without waiting.
      if (p_.clock.manual()) p_.clock.advance(kClosedManualStep);
      continue;
    }
    if (!p_.platform.presenting()) {
      play_unseen(now);
      continue;
    }
    if (p_.options.fps > 0.0 && now < next_frame) {
      if (p_.check.service_camera(now)) update_status(true);
      continue;
    }
    next_frame = std::max(next_frame + frame_interval, now);
    if (const std::optional<int> code = show_frame(now, frame_interval, stop, exit_code)) return *code;
  }
  return finish(exit_code);
}

int PlayLoop::finish(int exit_code) {
  p_.status.service().stopping();
  if (!p_.options.drm_writeback.empty() && exit_code == 0) {
    // What the display shows now, the last frame presented, read back from the display hardware.
    std::vector<std::uint8_t> rgba;
    platform::Size size;
    std::string error;
    if (p_.platform.capture_scanout(rgba, size, error) &&
        write_png(p_.options.drm_writeback, size.width, size.height, rgba, error)) {
      p_.out << "scanout of frame " << frame_ - 1 << " captured to " << p_.options.drm_writeback << "\n";
    } else {
      p_.err << "error: --drm-writeback: " << error << "\n";
      exit_code = 1;
    }
  }
  p_.kiosk.stopped();
  update_status(true);
  p_.out << "played " << frame_ << " frames, " << p_.status.errors().size() << " error(s)\n";
  return exit_code;
}

}  // namespace app
