// `player play`: opens the pieces of a play session (the board, the status, the event sources, the
// playlist, the platform and its drawer, the scene cache, the self-check) in the order their errors
// are told, and hands them to the play loop (play/play_loop.h); a GPU reset makes them anew
// (play/gpu_recovery.h).
#include "app/play_command.h"
#include "app/render_command.h"
#include "base/read_file.h"
#include "camera_script.h"
#include "control/server.h"

#include "base/parse.h"
#include "gl/caps.h"
#include "gl/gl_api.h"
#include "gl/session.h"
#include "hal/board.h"
#include "hal/devices.h"
#include "loader.h"
#include "platform/platform.h"
#include "play/bundle_follower.h"
#include "play/event_sources.h"
#include "play/frame_drawer.h"
#include "play/gpu_recovery.h"
#include "play/kiosk_state.h"
#include "play/play_clock.h"
#include "play/play_loop.h"
#include "play/scene_cache.h"
#include "play/self_check_session.h"
#include "play/status_reporter.h"
#include "render/renderer.h"
#include "shader_cache.h"

#include <chrono>
#include <cstdio>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <ostream>

namespace app {
namespace {

namespace fs = std::filesystem;

bool is_playlist(const std::string& path) {
  return fs::path(path).extension() == ".toml";
}

// The board file (or the built-in mock board) and its devices on the backend the options choose.
bool open_board(const PlayOptions& options, const hal::Clock& clock, hal::BoardConfig& board, hal::Devices& devices,
                std::ostream& err) {
  hal::Backend backend = hal::Backend::mock;
  if (!options.hal.empty()) {
    if (!hal::parse_backend(options.hal, backend)) {
      err << "error: --hal: expected linux or mock, got '" << options.hal << "'\n";
      return false;
    }
  } else if (!options.board_file.empty()) {
    backend = hal::Backend::linux_kernel;
  }
  try {
    board = options.board_file.empty() ? hal::builtin_mock_board() : hal::load_board(options.board_file);
    if (!options.buttons_script.empty()) board.mock_button_script = options.buttons_script;
    if (!options.status_file.empty()) board.status_file = options.status_file;
    if (!options.control.empty()) board.control = options.control == "off" ? "" : options.control;
    if (!options.metrics_file.empty()) board.metrics_file = options.metrics_file;
    if (backend == hal::Backend::linux_kernel && !options.buttons_script.empty()) {
      err << "error: --buttons-script drives mock buttons; add --hal mock\n";
      return false;
    }
    devices = hal::open_devices(board, backend, clock);
  } catch (const hal::ConfigError& e) {
    err << "error: " << e.what() << "\n";
    return false;
  }
  return true;
}

// --camera-script, for the mock camera.
bool load_camera_script(const PlayOptions& options, const hal::Devices& devices, std::vector<CameraStep>& steps,
                        std::ostream& err) {
  if (options.camera_script.empty()) return true;
  if (devices.mock_camera == nullptr) {
    err << "error: --camera-script drives the mock camera: add --hal mock and a board with a camera\n";
    return false;
  }
  std::string text, error;
  if (!base::read_regular_file(options.camera_script, "camera script", hal::kMaxScriptBytes, text, error) ||
      !parse_camera_script_text(text, options.camera_script, steps, error)) {
    err << "error: " << error << "\n";
    return false;
  }
  return true;
}

// One playlist file, or the command line's scenes as a playlist.
bool load_what_to_play(const PlayOptions& options, const playback::ParseOptions& parse_options, std::string& playlist_path,
                       std::shared_ptr<const playback::Playlist>& playlist, std::ostream& err) {
  std::vector<std::string> inputs = options.inputs;
  if (inputs.empty()) inputs.push_back("builtin:demo");
  if (inputs.size() == 1 && is_playlist(inputs.front())) {
    // A bundle's current/playlist.toml plays from the version the link leads to (bundle_follower.h).
    playlist_path = BundleFollower::resolve(fs::absolute(inputs.front()).lexically_normal().string());
    auto loaded = std::make_shared<playback::Playlist>();
    std::string error;
    if (!playback::load_playlist(playlist_path, parse_options, *loaded, error)) {
      err << "error: " << error << "\n";
      return false;
    }
    playlist = std::move(loaded);
    return true;
  }
  for (const std::string& input : inputs)
    if (is_playlist(input)) {
      err << "error: " << input << ": a playlist plays on its own (give one playlist, or scenes)\n";
      return false;
    }
  auto from_scenes =
      std::make_shared<playback::Playlist>(playback::playlist_from_scenes(inputs, options.duration_s, options.period_s));
  for (playback::Item& item : from_scenes->items) item.environment = parse_options.default_environment;
  playlist = std::move(from_scenes);
  return true;
}

platform::Options platform_options(const PlayOptions& options, std::string_view name) {
  platform::Options platform_options;
  platform_options.name = name;
  platform_options.display = true;
  platform_options.size = {options.width, options.height};
  platform_options.fullscreen = options.fullscreen;
  platform_options.drm_device = options.drm_device;
  platform_options.drm_connector = options.drm_connector;
  platform_options.drm_mode = options.drm_mode;
  platform_options.drm_atomic = options.drm_atomic;
  return platform_options;
}

int play_session(const PlayOptions& options, std::ostream& out, std::ostream& err, const Resume& resume, Resume& next,
                 std::string& remake_reason) {
  // The platform is named before anything opens, because it decides the clock: one that shows
  // frames on a display runs on real time, headless runs on the reproducible manual clock.
  std::string platform_why;
  const std::string platform_name =
      options.platform == "auto" ? std::string(platform::choose_auto(platform_why)) : options.platform;
  const platform::Capabilities capabilities = platform::capabilities(platform_name);
  PlayClock clock(options.fps <= 0.0 && !capabilities.shows_frames_on_a_display, resume.start, resume.wall_start,
                  resume.manual_now);

  hal::BoardConfig board;
  hal::Devices devices;
  if (!open_board(options, clock.devices(), board, devices, err)) return 1;
  KioskState kiosk;
  StatusReporter status(*devices.status, kiosk, clock, err);
  for (const std::string& problem : devices.problems) status.report(ErrorKind::device, problem);
  std::vector<CameraStep> camera_script;
  if (!load_camera_script(options, devices, camera_script, err)) return 1;
  SignalSource signals;
  ContentWatch watch;
  const bool signals_open = signals.open();
  std::string error;
  if (!watch.open(error)) status.report(ErrorKind::content, error);
  if (!signals_open) return 1;
  control::Server control;
  if (!board.control.empty()) {
    // A kiosk plays on without its socket: the problem is reported where its other problems are.
    if (control.open(board.control, {}, error))
      out << "control: listening on " << board.control << "\n";
    else
      status.report(ErrorKind::control, error);
  }
  if (!status.service().error().empty()) status.report(ErrorKind::service, status.service().error());
  status.announce_state();                     // `systemctl status` says starting while the shaders compile
  status.set_leds(!devices.problems.empty());  // nothing else can warn yet

  playback::ParseOptions parse_options;
  parse_options.content_root = options.content_root;
  parse_options.validate_setting = render::validate_setting;
  if (!options.environment.empty() && options.environment.rfind("builtin:", 0) != 0)
    parse_options.default_environment = fs::absolute(options.environment).lexically_normal().string();
  else
    parse_options.default_environment = options.environment;
  Loader loader(parse_options);
  std::string playlist_path;
  std::shared_ptr<const playback::Playlist> playlist;
  if (!load_what_to_play(options, parse_options, playlist_path, playlist, err)) return 1;

  const std::string shader_dir = shader_cache_dir(options.shader_cache);
  const std::string driver_cache_problem = prepare_driver_cache(shader_dir);
  const std::unique_ptr<gl::Session> session = gl::Session::open(platform_options(options, platform_name), error);
  if (!session) {
    err << "error: " << error << "\n";
    return 2;
  }
  const std::string shader_cache_line = open_program_store(*session, shader_dir);
  platform::Platform& platform = session->platform();
  const gl::Caps& caps = session->caps();
  // Textures beyond what this GPU can hold are drawn white with a warning, not failed at upload.
  loader.set_scene_options(load_options_for(caps));
  FrameDrawer drawer(*session, options.settings);
  if (!drawer.open(options.rotation >= 0 ? options.rotation : board.display_rotation, error)) {
    err << "error: " << error << "\n";
    return 2;
  }
  drawer.show_overlay(options.overlay == "on" || (options.overlay == "auto" && capabilities.desktop_window),
                      devices.status->led_count());
  out << "platform: " << platform.name() << " (" << platform.description() << "; " << caps.renderer << ")"
      << (platform_why.empty() ? "" : ", chosen because " + platform_why) << "\n";
  if (!platform.presenting()) {
    out << "display: " << platform.not_presenting_reason() << "; waiting for one\n";
    kiosk.display_lost();
  }
  out << shader_cache_line << (driver_cache_problem.empty() ? "" : "; Mesa's own: " + driver_cache_problem) << "\n";
  out << "playing " << (playlist_path.empty() ? std::string("the command line's scenes") : playlist_path) << ": "
      << playlist->items.size() << " item(s)\n"
      << std::flush;
  status.open_log(options.log_file, resume.resumed);
  if (!board.metrics_file.empty()) {
    Metrics base;
    base.version = PLAYER_VERSION;
    base.platform = platform.name();
    base.renderer = caps.renderer;
    base.start_unix_s = resume.wall_start;
    status.open_metrics(board.metrics_file, base);
    status.gpu_reset_survived(resume.gpu_resets);
  }
  if (!options.out_dir.empty()) fs::create_directories(options.out_dir);

  ButtonActions buttons(board.buttons, devices.mock_buttons);
  SceneCache scenes(loader, caps, status, err);
  SelfCheckSession check(devices.camera.get(), devices.mock_camera, std::move(camera_script), board.self_check_interval_s,
                         clock.devices(), status, kiosk);
  PlayLoop loop({options, out, err, clock, devices, kiosk, status, signals, watch, buttons, loader, platform, drawer, scenes,
                 check, control, board.schedule ? &*board.schedule : nullptr},
                std::move(playlist_path), std::move(playlist), resume.frames);
  const int code = loop.run();
  next = {true, clock.start(), clock.wall_start(), clock.manual_now(), loop.frames(), resume.gpu_resets};
  remake_reason = loop.remake_reason();
  return code;
}

}  // namespace

bool parse_start_time(const std::string& text, double& unix_s, std::string& error) {
  long long seconds = 0;
  if (base::parse_int(text, 0, 253402300799, seconds)) {  // up to the year 9999
    unix_s = static_cast<double>(seconds);
    return true;
  }
  // RFC 3339 with whole seconds: the date, 'T', the time, then 'Z' or an offset +HH:MM / -HH:MM.
  int year = 0, offset_h = 0, offset_m = 0, consumed = 0;
  unsigned month = 0, day = 0, hour = 0, minute = 0, second = 0;
  char zone = 0;
  if (std::sscanf(text.c_str(), "%4d-%2u-%2uT%2u:%2u:%2u%c%n", &year, &month, &day, &hour, &minute, &second, &zone, &consumed) ==
          7 &&
      hour < 24 && minute < 60 && second < 60) {
    const std::chrono::year_month_day date{std::chrono::year(year), std::chrono::month(month), std::chrono::day(day)};
    bool zone_ok = zone == 'Z' && static_cast<size_t>(consumed) == text.size();
    if (zone == '+' || zone == '-') {
      int more = 0;
      zone_ok = std::sscanf(text.c_str() + consumed, "%2d:%2d%n", &offset_h, &offset_m, &more) == 2 && offset_h < 24 &&
                offset_m < 60 && static_cast<size_t>(consumed + more) == text.size() && more == 5;
    }
    if (date.ok() && zone_ok) {
      const long long offset_s = (zone == '-' ? -1 : 1) * (offset_h * 3600LL + offset_m * 60LL);
      unix_s = static_cast<double>(std::chrono::sys_days(date).time_since_epoch().count() * 86400LL + hour * 3600LL +
                                   minute * 60LL + second - offset_s);
      return true;
    }
  }
  error = "--start-time: expected a time as 2026-12-07T17:59:30Z, 2026-12-07T18:59:30+01:00 or Unix seconds, got '" + text + "'";
  return false;
}

int run_play(const PlayOptions& options, std::ostream& out, std::ostream& err) {
  return play_with_recovery(
      [&](const Resume& resume, Resume& next, std::string& reason) {
        Resume first = resume;
        if (!resume.resumed && options.start_time_s >= 0.0) first.wall_start = options.start_time_s;
        return play_session(options, out, err, first, next, reason);
      },
      out, err);
}

}  // namespace app
