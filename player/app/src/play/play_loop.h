#pragma once
// The play loop: one poll over every event source, then a frame when one is due. It owns nothing:
// play_command.cpp opens the pieces and hands them over; the loop passes events between them.
#include "app/play_command.h"
#include "control/server.h"
#include "hal/devices.h"
#include "loader.h"
#include "platform/platform.h"
#include "play/bundle_follower.h"
#include "play/event_sources.h"
#include "play/frame_drawer.h"
#include "play/gpu_recovery.h"
#include "play/kiosk_state.h"
#include "play/opening_schedule.h"
#include "play/play_clock.h"
#include "play/scene_cache.h"
#include "play/self_check_session.h"
#include "play/status_reporter.h"
#include "playback/timeline.h"

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace app {

// What a session is made of, opened by play_command.cpp.
struct PlayPieces {
  const PlayOptions& options;
  std::ostream& out;
  std::ostream& err;
  PlayClock& clock;
  hal::Devices& devices;
  KioskState& kiosk;
  StatusReporter& status;
  SignalSource& signals;
  ContentWatch& watch;
  ButtonActions& buttons;
  Loader& loader;
  platform::Platform& platform;
  FrameDrawer& drawer;
  SceneCache& scenes;
  SelfCheckSession& check;
  control::Server& control;                // closed when no socket was asked for
  const hal::OpeningHours* opening_hours;  // the board's [schedule]; null: always open
};

class PlayLoop {
 public:
  // `playlist_path`: the playlist file, watched and reloaded (empty: scenes from the command line).
  PlayLoop(const PlayPieces& pieces, std::string playlist_path, std::shared_ptr<const playback::Playlist> playlist,
           long long frames);
  // Plays until stopped: an exit code for run_play, or kRemake (see gpu_recovery.h).
  int run();
  long long frames() const { return frame_; }
  const std::string& remake_reason() const { return remake_reason_; }

 private:
  enum class Next : std::uint8_t { go_on, stop, remake };
  // Closed, the loop wakes this often (besides its events) to look at the time: a second is as close
  // as anyone watches an opening.
  static constexpr int kClosedPollMs = 1000;
  static constexpr double kClosedManualStep = 1.0;

  void update_status(bool force);
  void apply_playlist(std::shared_ptr<const playback::Playlist> playlist, double now);
  void watch_content();
  // Every source's pending events: stop now (a signal), remake, or go on; `closed`: the window
  // was closed, so this frame is the last.
  Next drain_events(bool& closed);
  void drain_content();
  void drain_loader();
  Next drain_platform(bool& closed);
  void wait_for_events(double next_frame);
  void read_buttons(double now);
  void act(hal::Action action, double now);
  void serve_control(double now);
  // The playlist (when there is a file) and every scene, loaded again: SIGHUP and `player ctl reload`.
  void reload_everything();
  std::string command(const control::Command& command, double now);
  // Asks for the cue's scenes and makes this frame's share of the uploads.
  void load_for(const playback::Cue& cue);
  void play_unseen(double now);
  // The opening hours (or a display command) switch the display on or off: the platform switches
  // it, the state says closed, and opening runs a self-check.
  void follow_schedule(double now);
  // Closed: the clock runs on and the scene of the hour loads, nothing is drawn.
  void stay_closed(double now);
  playback::Cue cue_at(double now);
  void draw(const playback::Cue& cue);
  // Draws, writes and presents a frame. An exit code to return at once, or none; `stop`: this
  // frame was the last (--frames, the playlist's end, a display that took no frame).
  std::optional<int> show_frame(double now, double frame_interval, bool& stop, int& exit_code);
  int finish(int exit_code);

  PlayPieces p_;
  std::string playlist_path_;
  std::shared_ptr<const playback::Playlist> playlist_;
  std::unique_ptr<playback::Timeline> timeline_;
  GpuWatch gpu_;
  PollSet poll_;
  std::vector<ContentWatch::Change> changes_;
  std::vector<hal::Action> actions_;
  std::vector<int> control_fds_;
  OpeningSchedule schedule_;
  BundleFollower bundle_;            // a playlist in an installed content bundle: the next version at an item start
  std::uint64_t last_sequence_ = 0;  // the Cue::sequence of the last frame's item
  bool closed_ = false;              // the display is off by the schedule or a command
  bool screenshot_wanted_ = false;   // `player ctl screenshot`: the next frame drawn, written beside the socket
  long long frame_;
  int last_item_ = -1;
  double display_found_s_ = -1.0;  // when a display came (back), until its first frame is shown
  bool drew_scene_ = false;        // this frame shows a scene, not the loading screen or a check pattern
  bool scene_shown_;               // a scene frame was presented (or the loop resumed after a GPU reset)
  std::string remake_reason_;
  // Loads the image module (base/image_codec.h) for a camera, after the first frame. Last: joined
  // before anything above goes.
  std::jthread image_preload_;
};

}  // namespace app
