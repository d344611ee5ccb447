#include "app/play_command.h"
#include "app/render_command.h"
#include "camera_script.h"

#include "gl/caps.h"
#include "gl/gl_api.h"
#include "hal/board.h"
#include "hal/devices.h"
#include "hal/mock.h"
#include "hal/self_check.h"
#include "image_io.h"
#include "loader.h"
#include "render/light_field.h"
#include "overlay.h"
#include "service_notify.h"
#include "playback/timeline.h"
#include "render/renderer.h"
#include "render/rotation.h"

#include <poll.h>
#include <signal.h>
#include <sys/inotify.h>
#include <sys/signalfd.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <fstream>
#include <map>
#include <ostream>
#include <set>
#include <sstream>

namespace app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

// The states the status file and LEDs report.
// no_display: the kms platform has no display to show frames on (none connected, or another process
// holds it); the playlist clock runs on and nothing is drawn.
enum class State { starting, loading, playing, paused, error, no_display };
std::string_view name(State state) {
  switch (state) {
    case State::starting: return "starting";
    case State::loading: return "loading";
    case State::playing: return "playing";
    case State::paused: return "paused";
    case State::error: return "error";
    case State::no_display: return "no display";
  }
  return "?";
}

// LED patterns: the status LED tells the state, the error LED problems. Documented in board/README.md.
struct LedPlan {
  hal::LedPattern status, error;
};
LedPlan led_plan(State state, bool warning, bool check_failed) {
  LedPlan plan{hal::LedPattern::Off, hal::LedPattern::Off};
  switch (state) {
    case State::starting: plan.status = hal::LedPattern::BlinkFast; break;
    case State::loading: plan.status = hal::LedPattern::BlinkSlow; break;
    case State::playing: plan.status = hal::LedPattern::Heartbeat; break;
    case State::paused: plan.status = hal::LedPattern::On; break;
    case State::error: plan.error = hal::LedPattern::On; break;
    case State::no_display: plan.status = hal::LedPattern::BlinkSlow; break;
  }
  if (state != State::error) plan.error = check_failed ? hal::LedPattern::BlinkFast : warning ? hal::LedPattern::BlinkSlow : hal::LedPattern::Off;
  return plan;
}

// A scene on its way to the GPU or there.
struct Loaded {
  std::unique_ptr<render::SceneGpu> gpu;  // what draws
  scene::Bounds bounds;
  // A new version uploading in slices; it replaces `gpu` once whole, so a reload never shows half a scene.
  std::unique_ptr<render::SceneGpu> incoming;
  scene::Bounds incoming_bounds;
  // The light field display the item is shown on (null: the platform's own 2D surface).
  std::shared_ptr<const lightfield::Display> display, incoming_display;
  std::string error;  // failed to load: the item is skipped
  std::vector<std::string> warnings;  // loaded anyway (a texture drawn white): in the status while it plays
  bool requested = false;
};

// Frame-to-frame times over a window, for the status file.
class FrameStats {
 public:
  void add(double ms) {
    window_[next_++ % window_.size()] = ms;
    count_ = std::min(count_ + 1, window_.size());
  }
  double percentile(double p) const {
    if (count_ == 0) return 0.0;
    std::array<double, 256> sorted{};
    std::copy_n(window_.begin(), count_, sorted.begin());
    std::sort(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(count_));
    return sorted[std::min(count_ - 1, static_cast<size_t>(p * static_cast<double>(count_)))];
  }

 private:
  std::array<double, 256> window_{};
  size_t next_ = 0, count_ = 0;
};

bool is_playlist(const std::string& path) { return fs::path(path).extension() == ".toml"; }

bool parse_camera_script(const std::string& path, std::vector<CameraStep>& out, std::string& error) {
  std::ifstream in(path);
  if (!in) {
    error = path + ": cannot open camera script";
    return false;
  }
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return parse_camera_script_text(text, path, out, error);
}

// Resident memory in KiB, from /proc/self/statm (only read when logging).
long resident_kib() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return resident * (sysconf(_SC_PAGESIZE) / 1024);
}

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

// run()'s answer when the platform must be made anew: the GPU was reset and the context told of it
// (every GL resource is gone), or the kms platform can only have its display again through a new
// open of the device. run_play makes a new Player (platform, context, programs, scenes) that plays
// on from where this one was.
constexpr int kRemake = -1;
// The process's code when the context is lost and cannot be rebuilt here (no reset notification,
// or resets that keep coming): a service manager restarts the player.
constexpr int kGpuLost = 4;

// Where a Player that lost its GPU context was: the next one plays on from there.
struct Resume {
  bool resumed = false;
  std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
  double wall_start = wall_seconds();
  hal::Nanos manual_now{0};
  long long frames = 0;
};

class Player {
 public:
  Player(const PlayOptions& options, std::ostream& out, std::ostream& err, const Resume& resume = {})
      : options_(options), out_(out), err_(err), resumed_(resume.resumed), manual_{resume.manual_now}, start_(resume.start),
        wall_start_(resume.wall_start), frame_(resume.frames) {}
  int run();
  Resume resume_point() const { return {true, start_, wall_start_, manual_.now(), frame_}; }
  const std::string& remake_reason() const { return remake_reason_; }

 private:
  bool set_up_hal();
  bool set_up_watch();
  void watch_content();
  void handle_loader();
  void handle_signals(bool& stop);
  void handle_inotify();
  void handle_buttons(double now);
  void handle_platform_events(bool& stop);
  void act(hal::Action action, double now);
  void request_scenes(const playback::Frame& frame);
  void step_uploads();
  void render_frame(const playback::Frame& frame);
  void update_status(bool force);
  void set_leds();
  void report(const std::string& error);
  bool scene_settled(int item) const;
  void start_self_check(double now);
  void draw_check_frame();
  void service_camera(double now);
  void apply_playlist(std::shared_ptr<const playback::Playlist> playlist, double now);
  // The loader's key of every item, made once per playlist: the frame loop looks scenes up by them
  // without building strings.
  void make_item_keys();
  const std::string& key_of(int item) const { return item_keys_[static_cast<size_t>(item)]; }
  render::FrameSettings settings_for(int item) const;
  // The frame's size and target for the surface's size and the board's rotation.
  bool configure_rotation(std::string& error);
  double now_seconds() const;

  const PlayOptions& options_;
  std::ostream& out_;
  std::ostream& err_;

  std::unique_ptr<platform::Platform> platform_;
  gl::Caps caps_;
  render::Programs programs_;
  render::ViewTargets targets_;
  render::PresentTarget surface_{};  // the platform's framebuffer
  render::PresentTarget present_{};  // where frames are drawn: the surface, or the rotation's target
  render::Rotation rotation_;
  int rotation_degrees_ = 0;
  gl::FrameTimer timer_;

  std::string playlist_path_;  // empty: scenes from the command line
  std::shared_ptr<const playback::Playlist> playlist_;
  std::unique_ptr<playback::Timeline> timeline_;
  std::unique_ptr<Loader> loader_;
  std::map<std::string, Loaded> scenes_;
  std::vector<std::string> item_keys_;  // load_key() of each playlist item
  std::string shown_spec_;  // the scene the targets are configured for
  int configured_item_ = -2;
  std::uint64_t configured_sequence_ = 0;

  // Button actions that change how a frame is drawn.
  bool ao_override_ = false, ao_on_ = true;
  int output_offset_ = 0;

  // Clocks: without --fps a headless run advances 1/30 s a frame on a manual clock, so a run is
  // reproducible; otherwise the monotonic clock.
  bool manual_clock_ = false;
  bool resumed_ = false;
  hal::ManualClock manual_;
  hal::MonotonicClock monotonic_;
  const hal::Clock* hal_clock_ = &monotonic_;
  Clock::time_point start_;
  double wall_start_;
  long long frame_;
  bool context_lost_ = false;  // GL_CONTEXT_LOST without reset notification: nothing to rebuild from
  std::string remake_reason_;  // why run() returns kRemake

  hal::BoardConfig board_;
  hal::Devices devices_;
  std::vector<hal::ButtonConfig> buttons_;  // actions per button index
  std::optional<size_t> status_led_, error_led_;
  hal::MockCamera* mock_camera_ = nullptr;

  State state_ = State::starting;
  std::vector<std::string> errors_;
  std::optional<hal::CheckSummary> last_check_;
  bool check_requested_ = false;
  double next_check_ = 0.0;
  FrameStats stats_;
  double last_frame_s_ = -1.0;
  double display_found_s_ = -1.0;  // when a display came (back), until its first frame is shown
  double last_status_s_ = -1e9;
  std::string last_status_text_;
  std::ofstream log_;
  std::string pending_actions_;  // for the log line of the frame they act on
  std::array<bool, 256> long_fired_{};

  hal::DisplayChecker checker_;
  bool checking_ = false, camera_lost_ = false;
  double check_started_ = 0.0;
  std::uint32_t check_sequence_ = 0;
  hal::FiducialLayout check_layout_;
  hal::RgbImage check_image_, capture_;
  gl::Texture check_texture_;
  gl::Framebuffer check_fbo_;

  render::View view_;
  scene::Bounds shown_bounds_;
  // Items on a light field display: its views and outputs, and the targets they share.
  render::LightFieldOutput light_field_;
  render::ViewTargets light_field_targets_;
  bool shown_display_ = false;
  std::string gl_error_, last_status_error_;
  int last_item_ = -1;
  double last_error_s_ = -1e9;
  std::vector<CameraStep> camera_script_;
  size_t next_camera_step_ = 0;
  std::uint64_t swaps_ = 0;  // scenes replaced by a newer version of their file
  Clock::time_point last_log_ = Clock::now();

  Overlay overlay_;
  bool overlay_on_ = false;
  std::vector<Overlay::Lamp> lamps_;

  hal::UniqueFd signal_fd_, inotify_fd_;
  ServiceNotifier service_;  // systemd: READY, WATCHDOG, STATUS, STOPPING (board/ssao-player.service)
  std::map<int, std::string> watched_dirs_;  // watch descriptor -> folder
};

bool Player::configure_rotation(std::string& error) {
  surface_ = {platform_->framebuffer(), 0, 0, platform_->srgb_framebuffer()};
  const platform::Size size = platform_->size();
  if (!rotation_.configure(programs_, rotation_degrees_, size.width, size.height, surface_.srgb, error)) return false;
  present_ = rotation_.target(surface_);
  return true;
}

double Player::now_seconds() const {
  if (manual_clock_) return std::chrono::duration<double>(manual_.now()).count();
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

void Player::report(const std::string& error) {
  err_ << "warning: " << error << "\n";
  last_error_s_ = now_seconds();
  if (std::find(errors_.begin(), errors_.end(), error) != errors_.end()) return;
  errors_.push_back(error);
  constexpr size_t kKeep = 16;  // the recent ones; the oldest go first
  if (errors_.size() > kKeep) errors_.erase(errors_.begin());
}

bool Player::set_up_hal() {
  hal::Backend backend = hal::Backend::Mock;
  if (!options_.hal.empty()) {
    if (!hal::parse_backend(options_.hal, backend)) {
      err_ << "error: --hal: expected linux or mock, got '" << options_.hal << "'\n";
      return false;
    }
  } else if (!options_.board_file.empty()) {
    backend = hal::Backend::Linux;
  }
  try {
    board_ = options_.board_file.empty() ? hal::builtin_mock_board() : hal::load_board(options_.board_file);
    if (!options_.buttons_script.empty()) board_.mock_button_script = options_.buttons_script;
    if (!options_.status_file.empty()) board_.status_file = options_.status_file;
    if (backend == hal::Backend::Linux && !options_.buttons_script.empty()) {
      err_ << "error: --buttons-script drives mock buttons; add --hal mock\n";
      return false;
    }
    devices_ = hal::open_devices(board_, backend, *hal_clock_);
  } catch (const hal::ConfigError& e) {
    err_ << "error: " << e.what() << "\n";
    return false;
  }
  buttons_ = board_.buttons;
  for (const std::string& problem : devices_.problems) report(problem);
  status_led_ = devices_.status->find_led("status");
  error_led_ = devices_.status->find_led("error");
  if (backend == hal::Backend::Mock) mock_camera_ = dynamic_cast<hal::MockCamera*>(devices_.camera.get());
  if (!options_.camera_script.empty()) {
    std::string error;
    if (mock_camera_ == nullptr) {
      err_ << "error: --camera-script drives the mock camera: add --hal mock and a board with a camera\n";
      return false;
    }
    if (!parse_camera_script(options_.camera_script, camera_script_, error)) {
      err_ << "error: " << error << "\n";
      return false;
    }
  }
  if (board_.self_check_interval_s > 0.0) next_check_ = board_.self_check_interval_s;
  return true;
}

bool Player::set_up_watch() {
  sigset_t signals;
  sigemptyset(&signals);
  for (int signal : {SIGTERM, SIGINT, SIGHUP, SIGUSR1}) sigaddset(&signals, signal);
  // Blocked in every thread (the loader thread inherits the mask), read through the signalfd.
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  signal_fd_.reset(signalfd(-1, &signals, SFD_NONBLOCK | SFD_CLOEXEC));
  inotify_fd_.reset(inotify_init1(IN_NONBLOCK | IN_CLOEXEC));
  if (!inotify_fd_) report("inotify: cannot watch the content for changes (" + std::string(std::strerror(errno)) + ")");
  return static_cast<bool>(signal_fd_);
}

// Folders of the playlist and of every item's scene and display: a writer saves a dot-file and renames it into
// place (MOVED_TO), or writes in place (CLOSE_WRITE); a removed file (DELETE) fails its next load.
void Player::watch_content() {
  if (!inotify_fd_) return;
  std::set<std::string> folders;
  if (!playlist_path_.empty()) folders.insert(fs::path(playlist_path_).parent_path().string());
  for (const playback::Item& item : playlist_->items) {
    if (item.scene.rfind("builtin:", 0) != 0) folders.insert(fs::path(item.scene).parent_path().string());
    if (!item.display.empty()) folders.insert(fs::path(item.display).parent_path().string());
  }
  for (const std::string& folder : folders) {
    bool known = false;
    for (const auto& [wd, dir] : watched_dirs_) known = known || dir == folder;
    if (known) continue;
    const int wd = inotify_add_watch(inotify_fd_.get(), folder.c_str(), IN_CLOSE_WRITE | IN_MOVED_TO | IN_DELETE);
    if (wd >= 0) watched_dirs_[wd] = folder;
    else report(folder + ": cannot watch for changes (" + std::string(std::strerror(errno)) + ")");
  }
}

render::FrameSettings Player::settings_for(int item) const {
  render::FrameSettings settings = options_.settings;
  settings.width = rotation_.width();
  settings.height = rotation_.height();
  if (item >= 0 && item < static_cast<int>(playlist_->items.size())) {
    const playback::Item& entry = playlist_->items[static_cast<size_t>(item)];
    std::string ignored;  // validated when the playlist was read
    for (const playback::Setting& setting : entry.settings) render::apply_setting(settings, setting.key, setting.value, ignored);
    if (entry.has_background) settings.background = entry.background;
  }
  if (ao_override_) settings.ao = ao_on_;
  constexpr int kOutputs = static_cast<int>(std::size(render::kOutputNames));
  settings.output = static_cast<render::Output>((static_cast<int>(settings.output) + output_offset_) % kOutputs);
  return settings;
}

void Player::make_item_keys() {
  item_keys_.clear();
  for (const playback::Item& item : playlist_->items) item_keys_.push_back(load_key(item));
}

void Player::apply_playlist(std::shared_ptr<const playback::Playlist> playlist, double now) {
  playlist_ = std::move(playlist);
  make_item_keys();
  if (timeline_) timeline_->replace(*playlist_, now);
  else timeline_ = std::make_unique<playback::Timeline>(*playlist_, now, wall_start_ + now);
  configured_item_ = -2;
  // Scenes no item names any more are dropped with their GPU data.
  for (auto it = scenes_.begin(); it != scenes_.end();) {
    bool used = false;
    for (const std::string& key : item_keys_) used = used || key == it->first;
    it = used ? std::next(it) : scenes_.erase(it);
  }
  for (size_t i = 0; i < playlist_->items.size(); ++i) {
    auto found = scenes_.find(key_of(static_cast<int>(i)));
    if (found != scenes_.end() && !found->second.error.empty()) timeline_->set_playable(static_cast<int>(i), false);
  }
  watch_content();
}

void Player::request_scenes(const playback::Frame& frame) {
  for (int item : {frame.item, frame.next_item}) {
    if (item < 0) continue;
    const std::string& spec = key_of(item);
    Loaded& loaded = scenes_[spec];
    if (!loaded.requested) {
      loaded.requested = true;
      loader_->load_scene(spec);
    }
  }
}

void Player::handle_loader() {
  Loader::Result result;
  while (loader_->take(result)) {
    if (result.kind == Loader::Result::Kind::playlist) {
      if (!result.error.empty()) {
        report(result.error + " (the last good playlist keeps playing)");
        continue;
      }
      // Scenes it names anew load when their items come up; changed scene files come through inotify.
      apply_playlist(result.playlist, now_seconds());
      continue;
    }
    auto found = scenes_.find(result.path);
    if (found == scenes_.end()) continue;  // no longer in the playlist
    Loaded& loaded = found->second;
    if (!result.error.empty()) {
      report(result.error);
      if (!loaded.gpu) {  // never loaded: skip its items; a reload that fails keeps the old content
        loaded.error = result.error;
        for (size_t i = 0; i < playlist_->items.size(); ++i)
          if (key_of(static_cast<int>(i)) == result.path) timeline_->set_playable(static_cast<int>(i), false);
      }
      continue;
    }
    loaded.error.clear();
    loaded.warnings = std::move(result.warnings);
    for (const std::string& warning : loaded.warnings) err_ << "warning: " << warning << "\n";
    for (size_t i = 0; i < playlist_->items.size(); ++i)
      if (key_of(static_cast<int>(i)) == result.path) timeline_->set_playable(static_cast<int>(i), true);
    loaded.incoming_display = result.display;
    loaded.incoming = std::make_unique<render::SceneGpu>();
    loaded.incoming->begin(result.scene, caps_);
    loaded.incoming_bounds = result.scene->bounds;
  }
}

// Uploads in slices: a budget per frame keeps an item change or a reload from showing as a hitch.
void Player::step_uploads() {
  constexpr size_t kBudget = 8u << 20;
  size_t left = kBudget;
  for (auto& [spec, loaded] : scenes_) {
    if (!loaded.incoming || left == 0) continue;
    const size_t before = loaded.incoming->bytes();
    const bool done = loaded.incoming->step(left);
    left -= std::min(left, std::max<size_t>(loaded.incoming->bytes() - before, 1));
    if (!done) continue;
    if (loaded.incoming->failed()) {
      report(spec + ": " + loaded.incoming->error());
      loaded.incoming.reset();
      continue;
    }
    if (loaded.gpu) ++swaps_;
    loaded.gpu = std::move(loaded.incoming);
    loaded.bounds = loaded.incoming_bounds;
    loaded.display = loaded.incoming_display;
    if (spec == shown_spec_) configured_item_ = -2;  // the radius may have changed: configure again
  }
}

void Player::handle_signals(bool& stop) {
  signalfd_siginfo info{};
  while (read(signal_fd_.get(), &info, sizeof info) == static_cast<ssize_t>(sizeof info)) {
    switch (info.ssi_signo) {
      case SIGTERM:
      case SIGINT: stop = true; break;
      case SIGHUP:  // reload everything
        if (!playlist_path_.empty()) loader_->load_playlist(playlist_path_);
        for (auto& [spec, loaded] : scenes_) loader_->load_scene(spec);
        break;
      case SIGUSR1: check_requested_ = true; break;
      default: break;
    }
  }
}

void Player::handle_inotify() {
  alignas(inotify_event) char buffer[4096];
  for (;;) {
    const ssize_t n = read(inotify_fd_.get(), buffer, sizeof buffer);
    if (n <= 0) return;
    for (ssize_t at = 0; at < n;) {
      const auto* event = reinterpret_cast<const inotify_event*>(buffer + at);
      at += static_cast<ssize_t>(sizeof(inotify_event) + event->len);
      if (event->len == 0 || event->name[0] == '.') continue;  // dot-files are writers' temporaries
      const auto folder = watched_dirs_.find(event->wd);
      if (folder == watched_dirs_.end()) continue;
      const std::string path = (fs::path(folder->second) / event->name).string();
      if (path == playlist_path_) {
        if (event->mask & IN_DELETE) report(path + ": the playlist was deleted (the last good one keeps playing)");
        else loader_->load_playlist(path);
        continue;
      }
      // A deleted scene or display fails to load and is reported; the last good version keeps playing.
      for (const auto& [key, loaded] : scenes_)
        if (scene_of(key) == path || display_of(key) == path) loader_->load_scene(key);
    }
  }
}

void Player::act(hal::Action action, double now) {
  if (!pending_actions_.empty()) pending_actions_ += ",";
  pending_actions_ += hal::to_string(action);
  switch (action) {
    case hal::Action::none: break;
    case hal::Action::next: timeline_->next(now); break;
    case hal::Action::previous: timeline_->previous(now); break;
    case hal::Action::restart: timeline_->restart(now); break;
    case hal::Action::pause:
      if (timeline_->paused()) timeline_->resume(now);
      else timeline_->pause(now);
      break;
    case hal::Action::ao:
      ao_on_ = ao_override_ ? !ao_on_ : !options_.settings.ao;
      ao_override_ = true;
      configured_item_ = -2;
      break;
    case hal::Action::output:
      ++output_offset_;
      configured_item_ = -2;
      break;
    case hal::Action::check: check_requested_ = true; break;
  }
}

void Player::handle_buttons(double now) {
  std::array<hal::ButtonEvent, 32> events;
  for (;;) {
    const size_t n = devices_.buttons->read(events);
    for (size_t i = 0; i < n; ++i) {
      const hal::ButtonEvent& event = events[i];
      if (event.button >= buttons_.size()) continue;
      const hal::ButtonConfig& button = buttons_[event.button];
      // A button with a long-press action acts on release of a short press, so a long press does
      // not first do the short action; one without acts at once on press (and on each repeat).
      const bool has_long = button.long_action != hal::Action::none;
      switch (event.action) {
        case hal::ButtonAction::Press:
          if (!has_long) act(button.action, now);
          long_fired_[event.button] = false;
          break;
        case hal::ButtonAction::Repeat:
          if (!has_long) act(button.action, now);
          break;
        case hal::ButtonAction::LongPress:
          if (has_long) {
            act(button.long_action, now);
            long_fired_[event.button] = true;
          }
          break;
        case hal::ButtonAction::Release:
          if (has_long && !long_fired_[event.button]) act(button.action, now);
          break;
      }
    }
    if (n < events.size()) break;
  }
  if (!devices_.buttons->last_error().empty()) report(devices_.buttons->last_error());
}

void Player::handle_platform_events(bool& stop) {
  std::array<platform::Event, 16> events;
  const size_t n = platform_->drain_events(events);
  for (size_t i = 0; i < n; ++i) {
    const platform::Event& event = events[i];
    switch (event.type) {
      case platform::EventType::close_requested: stop = true; break;
      case platform::EventType::resized: {
        configured_item_ = -2;
        std::string error;
        if (!configure_rotation(error)) report(error);
        break;
      }
      case platform::EventType::display_lost:
        out_ << "display: " << platform_->not_presenting_reason() << " at " << now_seconds() << " s; the playlist plays on unseen\n"
             << std::flush;
        state_ = State::no_display;
        update_status(true);
        break;
      case platform::EventType::display_found:
        out_ << "display: " << platform_->description() << " at " << now_seconds() << " s\n" << std::flush;
        display_found_s_ = now_seconds();
        configured_item_ = -2;
        break;
      case platform::EventType::warning: report(platform_->last_error()); break;
      case platform::EventType::remake: remake_reason_ = platform_->last_error(); break;
      case platform::EventType::key_press:
      case platform::EventType::key_release:
        if (auto* mock = dynamic_cast<hal::MockButtons*>(devices_.buttons.get()))
          for (size_t b = 0; b < buttons_.size(); ++b)
            if (!buttons_[b].key.empty() && buttons_[b].key == event.key)
              mock->inject(b, event.type == platform::EventType::key_press);
        break;
    }
  }
}


// The display self-check: one frame with AprilTag markers in the corners is held on screen until
// the camera delivers a capture of it (or a timeout), then compared. The playlist clock runs on.
void Player::start_self_check(double now) {
  check_requested_ = false;
  if (!devices_.camera) {
    report("self-check: the board has no camera");
    return;
  }
  const int w = rotation_.width(), h = rotation_.height();
  const std::vector<uint8_t> rgba = render::read_presented(present_, w, h);
  check_image_.resize(w, h);
  for (size_t i = 0, n = static_cast<size_t>(w) * static_cast<size_t>(h); i < n; ++i)
    std::copy_n(&rgba[i * 4], 3, &check_image_.pixels[i * 3]);
  check_layout_ = hal::FiducialLayout::for_display(w, h, ++check_sequence_);
  hal::draw_fiducials(check_image_, check_layout_);
  // Uploaded in the framebuffer's own encoding, so the blit copies the bytes as they are.
  std::vector<uint8_t> flipped(static_cast<size_t>(w) * static_cast<size_t>(h) * 4, 255);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      std::copy_n(check_image_.at(x, h - 1 - y), 3, &flipped[(static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x)) * 4]);
  check_texture_ = gl::make_texture();
  gl::api.BindTexture(GL_TEXTURE_2D, check_texture_.id());
  gl::api.TexStorage2D(GL_TEXTURE_2D, 1, present_.srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, w, h);
  gl::api.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl::api.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, flipped.data());
  check_fbo_ = gl::make_framebuffer();
  gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, check_fbo_.id());
  gl::api.FramebufferTexture2D(GL_READ_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, check_texture_.id(), 0);
  gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  check_started_ = now;
  checking_ = true;
  if (mock_camera_ != nullptr) mock_camera_->show(check_image_);
}

void Player::draw_check_frame() {
  const int w = rotation_.width(), h = rotation_.height();
  gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, check_fbo_.id());
  gl::api.BindFramebuffer(GL_DRAW_FRAMEBUFFER, present_.framebuffer);
  gl::api.BlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Player::service_camera(double now) {
  if (!devices_.camera) return;
  while (next_camera_step_ < camera_script_.size() && camera_script_[next_camera_step_].at_s <= now) {
    if (camera_script_[next_camera_step_++].plugged) mock_camera_->replug();
    else mock_camera_->unplug();
  }
  // The queue is drained before the stall check: after a long frame (shader compilation at start,
  // a slow board) a frame waiting there is not a stalled camera.
  const bool drained = !checking_ && devices_.camera->read_frame(capture_);
  devices_.camera->service();
  const bool lost = devices_.camera->state() != hal::CameraState::Streaming;
  if (lost != camera_lost_) {
    if (lost) report("camera: " + devices_.camera->last_error());
    camera_lost_ = lost;
    update_status(true);
  }
  if (!checking_) {
    if (!drained) devices_.camera->read_frame(capture_);  // keep the queue drained between checks
    return;
  }
  constexpr double kCheckTimeout = 3.0;
  if (devices_.camera->read_frame(capture_)) {
    const hal::SelfCheckResult result = checker_.check(check_image_, check_layout_, capture_);
    last_check_ = hal::CheckSummary{result.passed, result.score, result.reason, hal_clock_->now()};
    if (!result.passed) report("self-check failed: " + result.reason);
    checking_ = false;
  } else if (now - check_started_ > kCheckTimeout) {
    last_check_ = hal::CheckSummary{false, 0.0, "no camera frame within 3 s", hal_clock_->now()};
    report("self-check failed: no camera frame within 3 s");
    checking_ = false;
  }
  if (!checking_) {
    if (mock_camera_ != nullptr) mock_camera_->show(check_image_);  // the synthetic camera films the last frame shown
    update_status(true);
  }
}

void Player::render_frame(const playback::Frame& frame) {
  State state = State::playing;
  const render::SceneGpu* gpu = nullptr;
  if (frame.item < 0) {
    state = State::error;
  } else {
    const std::string& spec = key_of(frame.item);
    auto found = scenes_.find(spec);
    if (found != scenes_.end() && found->second.gpu && found->second.gpu->ready()) {
      gpu = found->second.gpu.get();
      const lightfield::Display* display = found->second.display.get();
      const bool new_item = frame.item != configured_item_ || frame.sequence != configured_sequence_ || spec != shown_spec_;
      if (new_item || frame.cut) {
        std::string error;
        render::FrameSettings settings = settings_for(frame.item);
        if (display != nullptr && display->type == lightfield::DisplayType::modules &&
            settings.ao_settings.estimator == ssao::Estimator::horizon) {
          // Horizon searches screen-space slices; Algorithm 2 for modules runs the hemisphere estimator.
          settings.ao_settings.estimator = ssao::Estimator::hemisphere;
        }
        const bool configured = display != nullptr ? light_field_.configure(programs_, caps_, *display, settings, found->second.bounds,
                                                                            gpu->radius(), light_field_targets_, error)
                                                   : targets_.configure(programs_, caps_, settings, gpu->radius(), present_.srgb, error);
        if (!configured) {
          report(spec + ": " + error);
          gpu = nullptr;
        }
        configured_item_ = frame.item;
        configured_sequence_ = frame.sequence;
        shown_spec_ = spec;
      }
      shown_display_ = gpu != nullptr && display != nullptr;
      if (gpu != nullptr) {
        shown_bounds_ = found->second.bounds;
        if (shown_display_) {
          const glm::ivec2 size = light_field_.view_size();
          light_field_.set_camera(scene::frame(shown_bounds_, framing_of(frame.camera), size.x, size.y));
        } else {
          view_ = render::view_of(
              scene::frame(shown_bounds_, framing_of(frame.camera), targets_.settings().width, targets_.settings().height));
        }
      }
    } else {
      state = State::loading;
    }
  }
  if (timeline_->paused() && state == State::playing) state = State::paused;
  if (state != state_) {
    state_ = state;
    update_status(true);  // sets the LEDs too
  }

  timer_.begin_frame();
  if (checking_) {
    draw_check_frame();
  } else if (gpu != nullptr && shown_display_) {
    // Every module or view, then what the display is fed (a quilt's panel image, the modules'
    // montage) scaled onto the surface. Per-pass times are per view here: the frame is not timed by pass.
    light_field_.render(programs_, *gpu, light_field_targets_, frame.fade, false, {}, &gl_error_);
    light_field_.present(programs_, present_, rotation_.width(), rotation_.height());
  } else if (gpu != nullptr) {
    const render::PassContext pass{programs_, *gpu, targets_, view_, &timer_, &gl_error_};
    render::render_view(pass, present_, frame.fade);
  } else {
    // Nothing to draw yet (loading) or nothing playable: the background colour.
    gl::api.BindFramebuffer(GL_FRAMEBUFFER, present_.framebuffer);
    gl::api.Viewport(0, 0, rotation_.width(), rotation_.height());
    const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    gl::api.ClearBufferfv(GL_COLOR, 0, black);
  }
  timer_.end_frame();
  // Pass times arrive a frame or two late; the automatic prepass choice is made from them.
  gl::FrameTimer::Times times;
  if (timer_.poll(times) && gpu != nullptr && !checking_ && !shown_display_)
    render::note_raster_time(targets_, render::to_pass_times(times, timer_.gpu_timed()));
  if (!gl_error_.empty()) {
    report("GL: " + gl_error_);
    gl_error_.clear();
  }
}

bool Player::scene_settled(int item) const {
  const auto found = scenes_.find(key_of(item));
  if (found == scenes_.end()) return false;
  const Loaded& loaded = found->second;
  return !loaded.error.empty() || (loaded.gpu && loaded.gpu->ready() && !loaded.incoming);
}

void Player::set_leds() {
  // A warning holds while a condition lasts (a camera lost) and for a minute after an error.
  constexpr double kErrorShownFor = 60.0;
  const bool content_warning = std::any_of(scenes_.begin(), scenes_.end(),
                                           [](const auto& entry) { return !entry.second.warnings.empty(); });
  const bool warning = camera_lost_ || !devices_.problems.empty() || content_warning ||
                       (!errors_.empty() && now_seconds() - last_error_s_ < kErrorShownFor);
  const LedPlan plan = led_plan(state_, warning, last_check_ && !last_check_->passed);
  if (status_led_ && devices_.status->pattern(*status_led_) != plan.status) devices_.status->set_pattern(*status_led_, plan.status);
  if (error_led_ && devices_.status->pattern(*error_led_) != plan.error) devices_.status->set_pattern(*error_led_, plan.error);
}

void Player::update_status(bool force) {
  service_.state(name(state_));  // before the period: a state change reaches systemd at once
  const double now = now_seconds();
  constexpr double kPeriod = 2.0;  // often enough for a monitor, rarely enough for an SD card
  if (!force && now - last_status_s_ < kPeriod) return;
  last_status_s_ = now;
  // GL errors are looked for here, every status period, not after each pass: glGetError costs a
  // round trip on some drivers. (--check-errors style per-pass checks are for tests and debugging.)
  if (platform_) {
    const GLenum gl_status = gl::api.GetError();
    if (gl_status == GL_CONTEXT_LOST_KHR) context_lost_ = true;
    if (gl_status != GL_NO_ERROR) {
      char text[64];
      std::snprintf(text, sizeof text, "GL error 0x%04x during playback", gl_status);
      report(text);
    }
  }
  set_leds();
  hal::StatusReport report;
  report.state = std::string(name(state_));
  if (timeline_ && last_item_ >= 0) report.item = playlist_->items[static_cast<size_t>(last_item_)].scene;
  report.frames = static_cast<std::uint64_t>(frame_);
  report.frame_ms_p50 = stats_.percentile(0.5);
  report.frame_ms_p99 = stats_.percentile(0.99);
  report.fps = report.frame_ms_p50 > 0.0 ? 1000.0 / report.frame_ms_p50 : 0.0;
  report.errors = errors_;
  report.warnings = devices_.problems;  // devices missing since start: the player goes on without them
  if (camera_lost_) report.warnings.push_back("camera: " + devices_.camera->last_error());
  for (const auto& [spec, loaded] : scenes_)
    report.warnings.insert(report.warnings.end(), loaded.warnings.begin(), loaded.warnings.end());
  report.self_check = last_check_;
  std::string error;
  if (!devices_.status->write_report(report, &error) && error != last_status_error_) {
    last_status_error_ = error;
    err_ << "warning: " << error << "\n";
  }
}

int Player::run() {
  // The platform is named before anything opens, because it decides the clock: a display (window,
  // kms) runs on real time, headless runs on the reproducible manual clock.
  std::string platform_why;
  const std::string platform_name =
      options_.platform == "auto" ? std::string(platform::choose_auto(platform_why)) : options_.platform;
  manual_clock_ = options_.fps <= 0.0 && platform_name != "window" && platform_name != "kms";
  if (manual_clock_) hal_clock_ = &manual_;
  if (!set_up_hal() || !set_up_watch()) return 1;
  if (!service_.error().empty()) report(service_.error());
  service_.state(name(state_));  // `systemctl status` says starting while the shaders compile
  set_leds();

  // What to play.
  playback::ParseOptions parse_options;
  parse_options.content_root = options_.content_root;
  parse_options.validate_setting = render::validate_setting;
  loader_ = std::make_unique<Loader>(parse_options);
  std::vector<std::string> inputs = options_.inputs;
  if (inputs.empty()) inputs.push_back("builtin:demo");
  if (inputs.size() == 1 && is_playlist(inputs.front())) {
    playlist_path_ = fs::absolute(inputs.front()).lexically_normal().string();
    auto playlist = std::make_shared<playback::Playlist>();
    std::string error;
    if (!playback::load_playlist(playlist_path_, parse_options, *playlist, error)) {
      err_ << "error: " << error << "\n";
      return 1;
    }
    playlist_ = std::move(playlist);
  } else {
    for (const std::string& input : inputs)
      if (is_playlist(input)) {
        err_ << "error: " << input << ": a playlist plays on its own (give one playlist, or scenes)\n";
        return 1;
      }
    playlist_ = std::make_shared<playback::Playlist>(playback::playlist_from_scenes(inputs, options_.duration_s, options_.period_s));
  }

  platform::Options platform_options;
  platform_options.name = platform_name;
  platform_options.display = true;
  platform_options.size = {options_.width, options_.height};
  platform_options.fullscreen = options_.fullscreen;
  platform_options.drm_device = options_.drm_device;
  platform_options.drm_connector = options_.drm_connector;
  platform_options.drm_mode = options_.drm_mode;
  platform_options.drm_atomic = options_.drm_atomic;
  std::string error;
  platform_ = gl::open_context(platform_options, error);
  if (!platform_) {
    err_ << "error: " << error << "\n";
    return 2;
  }
  caps_ = gl::query_caps();
  gl::install_debug_log(caps_, false);
  // Textures beyond what this GPU can hold are drawn white with a warning, not failed at upload.
  loader_->set_scene_options(load_options_for(caps_));
  surface_ = {platform_->framebuffer(), 0, 0, platform_->srgb_framebuffer()};
  rotation_degrees_ = options_.rotation >= 0 ? options_.rotation : board_.display_rotation;
  if (!configure_rotation(error)) {
    err_ << "error: " << error << "\n";
    return 2;
  }
  // Every SSAO variant now, so a playlist item with another estimator or precision does not compile mid-play.
  if (!programs_.build(caps_, error)) {
    err_ << "error: " << error << "\n";
    return 2;
  }
  for (ssao::Estimator estimator : ssao::kEstimators)
    for (ssao::Precision precision : ssao::kPrecisions)
      if (!programs_.ssao(estimator, precision, error)) {
        err_ << "error: " << error << "\n";
        return 2;
      }
  timer_.create(caps_.timer_query, false);
  overlay_on_ = options_.overlay == "on" || (options_.overlay == "auto" && platform_->name() == "window");
  lamps_.resize(devices_.status->led_count());
  out_ << "platform: " << platform_->name() << " (" << platform_->description() << "; " << caps_.renderer << ")"
       << (platform_why.empty() ? "" : ", chosen because " + platform_why) << "\n";
  if (!platform_->presenting()) {
    out_ << "display: " << platform_->not_presenting_reason() << "; waiting for one\n";
    state_ = State::no_display;
  }
  out_ << "playing " << (playlist_path_.empty() ? std::string("the command line's scenes") : playlist_path_) << ": "
       << playlist_->items.size() << " item(s)\n" << std::flush;
  if (!options_.log_file.empty()) log_.open(options_.log_file, resumed_ ? std::ios::app : std::ios::trunc);
  if (!options_.out_dir.empty()) fs::create_directories(options_.out_dir);

  make_item_keys();
  timeline_ = std::make_unique<playback::Timeline>(*playlist_, 0.0, wall_start_);
  watch_content();
  update_status(true);

  bool stop = false;
  int exit_code = 0;
  const double frame_interval = options_.fps > 0.0 ? 1.0 / options_.fps : 1.0 / 30.0;
  double next_frame = 0.0;
  std::vector<pollfd> fds;
  while (!stop) {
    // One poll over every source; it sleeps only until the next frame is due.
    fds.clear();
    for (int fd : {signal_fd_.get(), inotify_fd_.get(), loader_->fd(), platform_->event_fd(), devices_.buttons->fd(),
                   devices_.status->fd(), devices_.camera ? devices_.camera->fd() : -1})
      if (fd >= 0) fds.push_back({fd, POLLIN, 0});
    int timeout_ms = 0;
    if (!platform_->presenting()) timeout_ms = platform_->poll_interval_ms();
    else if (!manual_clock_ && options_.fps > 0.0)
      timeout_ms = std::max(0, static_cast<int>((next_frame - now_seconds()) * 1000.0));
    poll(fds.data(), fds.size(), timeout_ms);

    handle_signals(stop);
    if (stop) break;
    handle_inotify();
    handle_loader();
    handle_platform_events(stop);
    if (!remake_reason_.empty()) return kRemake;
    const double now = now_seconds();
    handle_buttons(now);
    devices_.status->update();
    if (!platform_->presenting()) {
      // No display to show on (kms: none connected, or another process holds it): the playlist
      // clock runs on and scenes keep loading, so a display that comes back shows the right item.
      if (state_ != State::no_display) {
        state_ = State::no_display;
        update_status(true);
      }
      const playback::Frame frame = timeline_->at(now, wall_start_ + now);
      last_item_ = frame.item;
      request_scenes(frame);
      step_uploads();
      service_camera(now);
      // The loop is alive and waiting, which is all the watchdog checks; READY=1 too, so a player
      // behind a switched-off TV starts as a service instead of timing out.
      service_.frame_presented(monotonic_.now());
      update_status(false);
      continue;
    }
    if (options_.fps > 0.0 && now < next_frame) {
      service_camera(now);
      continue;
    }
    next_frame = std::max(next_frame + frame_interval, now);

    if (check_requested_ && !checking_) start_self_check(now);
    if (board_.self_check_interval_s > 0.0 && now >= next_check_ && !checking_) {
      next_check_ = now + board_.self_check_interval_s;
      start_self_check(now);
    }
    playback::Frame frame = timeline_->at(now, wall_start_ + now);
    request_scenes(frame);
    step_uploads();
    if (manual_clock_) {
      // A reproducible run waits for the item's scene instead of showing frames of "loading".
      while (frame.item >= 0 && !scene_settled(frame.item)) {
        pollfd wake{loader_->fd(), POLLIN, 0};
        poll(&wake, 1, 100);
        handle_loader();
        frame = timeline_->at(now, wall_start_ + now);
        request_scenes(frame);
        step_uploads();
      }
    }
    last_item_ = frame.item;
    render_frame(frame);
    if (overlay_on_) {
      for (size_t led = 0; led < lamps_.size(); ++led)
        lamps_[led] = {devices_.status->led_name(led), hal::to_string(devices_.status->pattern(led)), devices_.status->level(led)};
      overlay_.update(name(state_), lamps_, present_.srgb);
      overlay_.draw(present_.framebuffer, rotation_.height());
    }
    if (!options_.out_dir.empty()) {
      char name[32];
      std::snprintf(name, sizeof name, "frame-%06lld.png", frame_);
      const std::vector<uint8_t> rgba = render::read_presented(present_, rotation_.width(), rotation_.height());
      if (!write_png((fs::path(options_.out_dir) / name).string(), rotation_.width(), rotation_.height(), rgba, error)) {
        err_ << "error: " << error << "\n";
        return 1;
      }
    }
    rotation_.finish(programs_, surface_);
    if (!options_.snapshot.empty() && frame_ + 1 == options_.frames) {
      // The last frame as the GPU drew it onto the surface, before it goes to the display.
      const std::vector<uint8_t> rgba = render::read_presented(surface_, platform_->size().width, platform_->size().height);
      if (!write_png(options_.snapshot, platform_->size().width, platform_->size().height, rgba, error)) {
        err_ << "error: --snapshot: " << error << "\n";
        return 1;
      }
    }
    if (!platform_->present()) {
      err_ << "error: " << platform_->last_error() << "\n";
      exit_code = 3;
      stop = true;
    } else service_.frame_presented(monotonic_.now());  // only presented frames feed the watchdog
    if (frame_ == 0) out_ << "first frame presented " << ms_since_process_start() << " ms after the process started\n" << std::flush;
    if (display_found_s_ >= 0.0 && platform_->presenting()) {
      out_ << "display: showing frames again " << (now_seconds() - display_found_s_) * 1000.0 << " ms after it came\n" << std::flush;
      display_found_s_ = -1.0;
    }
    service_camera(now);
    if (log_.is_open()) {
      log_ << frame_ << " t=" << now << " item=" << frame.item << " state=" << name(state_);
      for (size_t led = 0; led < devices_.status->led_count(); ++led)
        log_ << ' ' << devices_.status->led_name(led) << '=' << hal::to_string(devices_.status->pattern(led));
      const Clock::time_point logged = Clock::now();
      log_ << " actions=" << (pending_actions_.empty() ? "-" : pending_actions_) << " camera="
           << (camera_lost_ ? "lost" : "ok") << " swaps=" << swaps_ << " ms="
           << std::chrono::duration<double, std::milli>(logged - last_log_).count() << " rss_kib=" << resident_kib()
           << "\n" << std::flush;  // read while the player runs (tests, benchmarks)
      last_log_ = logged;
    }
    pending_actions_.clear();

    const double frame_s = manual_clock_ ? now : std::chrono::duration<double>(Clock::now() - start_).count();
    if (last_frame_s_ >= 0.0) stats_.add((frame_s - last_frame_s_) * 1000.0);
    last_frame_s_ = frame_s;
    ++frame_;
    update_status(false);
    if (manual_clock_) manual_.advance(std::chrono::duration_cast<hal::Nanos>(std::chrono::duration<double>(frame_interval)));
    if (options_.frames > 0 && frame_ >= options_.frames) break;
    // A reset is asked about every frame (a query the driver answers from the CPU side): after one,
    // every draw is dropped until the context is made anew.
    if (gl::api.GetGraphicsResetStatus != nullptr) {
      const GLenum reset = gl::api.GetGraphicsResetStatus();
      if (reset != GL_NO_ERROR) {
        remake_reason_ = std::string("the GPU was reset (") +
                         (reset == GL_GUILTY_CONTEXT_RESET_KHR     ? "caused by this player"
                          : reset == GL_INNOCENT_CONTEXT_RESET_KHR ? "caused elsewhere"
                                                                   : "cause unknown") +
                         ") at frame " + std::to_string(frame_ - 1);
        err_ << "warning: " << remake_reason_ << "\n";
        return kRemake;
      }
    }
    if (context_lost_) {
      err_ << "error: the GL context is lost and this driver does not tell of GPU resets, so nothing can be rebuilt; exiting ("
           << kGpuLost << ") for the service manager to restart the player\n";
      return kGpuLost;
    }
    if (frame.finished) break;
  }
  service_.stopping();
  if (!options_.drm_writeback.empty() && exit_code == 0) {
    // What the display shows now, the last frame presented, read back from the display hardware.
    std::vector<std::uint8_t> rgba;
    platform::Size size;
    if (platform_->capture_scanout(rgba, size, error) && write_png(options_.drm_writeback, size.width, size.height, rgba, error)) {
      out_ << "scanout of frame " << frame_ - 1 << " captured to " << options_.drm_writeback << "\n";
    } else {
      err_ << "error: --drm-writeback: " << error << "\n";
      exit_code = 1;
    }
  }
  state_ = state_ == State::error || state_ == State::no_display ? state_ : State::playing;
  update_status(true);
  out_ << "played " << frame_ << " frames, " << errors_.size() << " error(s)\n";
  return exit_code;
}

}  // namespace

int run_play(const PlayOptions& options, std::ostream& out, std::ostream& err) {
  Resume resume;
  std::string reason;
  std::vector<Clock::time_point> resets;
  for (;;) {
    Resume next;
    {
      Player player(options, out, err, resume);
      const int code = player.run();
      if (code != kRemake) return code;
      next = player.resume_point();
      reason = player.remake_reason();
    }  // every GL object, the context and the devices go before the next player opens them again
    // A GPU that resets again and again is not recovering here; a fresh process (or a reboot) may.
    const Clock::time_point now = Clock::now();
    resets.push_back(now);
    std::erase_if(resets, [&](Clock::time_point t) { return now - t > std::chrono::minutes(1); });
    if (resets.size() > 3) {
      err << "error: the platform had to be made anew " << resets.size() << " times within a minute (last: " << reason
          << "); exiting (" << kGpuLost << ") for the service manager to restart the player\n";
      return kGpuLost;
    }
    resume = next;
    out << "remake: the platform, its context and every GL resource are made anew (" << reason << "); playing on from frame "
        << resume.frames << "\n" << std::flush;
  }
}

}  // namespace app
