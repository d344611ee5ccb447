// The player's command line: a thin layer over the app library.
#include "app/check_command.h"
#include "app/content_command.h"
#include "app/ctl_command.h"
#include "app/play_command.h"
#include "app/render_command.h"
#include "base/parse.h"
#include "content/content.h"
#include "control/control.h"
#include "fleet/fleet.h"
#include "hal/devices.h"
#include "hal/hal_test.h"
#include "platform/platform.h"
#include "render/settings.h"
#include "scene/procedural.h"

#include <CLI/CLI.hpp>

#include <iostream>
#include <limits>
#include <vector>

namespace {

// Every render setting becomes --KEY, from the codec's table, with the default it reads back.
struct SettingOptions {
  std::vector<std::pair<std::string, std::string>> values;  // key, text given on the command line

  void add_to(CLI::App& command, const render::FrameSettings& defaults) {
    values.reserve(render::setting_keys().size());
    for (const render::SettingKey& key : render::setting_keys()) {
      values.emplace_back(std::string(key.key), std::string());
      command.add_option("--" + std::string(key.key), values.back().second, std::string(key.help) + " (" + key.choices + ")")
          ->default_str(render::setting_value(defaults, key.key));
    }
  }
  bool apply(render::FrameSettings& settings, std::string& error) const {
    for (const auto& [key, value] : values)
      if (!value.empty() && !render::apply_setting(settings, key, value, error)) {
        error = "--" + error;
        return false;
      }
    return true;
  }
};

bool parse_size(const std::string& text, int& width, int& height) {
  return base::parse_size(text, std::numeric_limits<int>::max(), width, height);
}

// --size and the settings options, which render and play share: false after printing the error.
bool apply_frame_options(const std::string& size, int& width, int& height, const SettingOptions& options,
                         render::FrameSettings& settings) {
  if (!parse_size(size, width, height)) {
    std::cerr << "error: --size: '" << size << "' is not WxH with positive integers (e.g. 1024x768)\n";
    return false;
  }
  std::string error;
  if (!options.apply(settings, error)) {
    std::cerr << "error: " << error << "\n";
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"player: a kiosk glTF player with screen-space ambient occlusion on OpenGL ES 3.1 compute"};

  const std::string shader_cache_help =
      "Folder that keeps compiled shaders between runs (Mesa's cache and program binaries), or off; default "
      "$CACHE_DIRECTORY/shaders (the service), else $XDG_CACHE_HOME or ~/.cache, /ssao-player/shaders";
  app::RenderOptions render;
  std::string size = "1024x768";
  auto* render_cmd = cli.add_subcommand("render", "Render one frame of SCENE to a PNG and print per-pass GPU times");
  std::string builtins;
  for (const std::string& name : scene::builtin_names()) builtins += " builtin:" + name;
  render_cmd->add_option("scene", render.scene, "A .gltf or .glb file, or a built-in scene:" + builtins)->required();
  render_cmd->add_option("-o,--output", render.output, "PNG file to write")->required();
  render_cmd->add_option("--size", size, "Image size WxH")->capture_default_str();
  render_cmd->add_option("--azimuth", render.framing.azimuth_deg, "Camera azimuth about +Y in degrees")->capture_default_str();
  render_cmd->add_option("--elevation", render.framing.elevation_deg, "Camera elevation in degrees")
      ->check(CLI::Range(-90.0, 90.0))
      ->capture_default_str();
  render_cmd
      ->add_option("--distance", render.framing.distance,
                   "Camera distance as a multiple of the distance that just fits the scene")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  render_cmd
      ->add_option("--file-camera", render.file_camera,
                   "View through the scene's own camera N (glTF's cameras, in the order the scene's nodes are visited) "
                   "instead of framing it; the aspect is the image's")
      ->check(CLI::NonNegativeNumber);
  render_cmd
      ->add_option("--time", render.time,
                   "Pose the scene's animations at T seconds (each selection loops over its longest animation)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  render_cmd
      ->add_option("--animation", render.animation,
                   "Which of the scene's animations pose it: all, none (the rest pose), an index or a name")
      ->capture_default_str();
  SettingOptions render_settings;
  render_settings.add_to(*render_cmd, render.frame);
  render_cmd->add_option("--platform", render.platform, "GL platform: " + platform::names_text())
      ->check(CLI::IsMember(platform::names()))
      ->capture_default_str();
  render_cmd->add_option("--frames", render.frames, "Frames to render; times are the median of all but the first")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  render_cmd->add_option("--dump", render.dump_dir,
                         "Write float EXRs (raw and blurred AO, world position, normal, linear depth) and camera.json to DIR "
                         "(with --display: each view's in DIR/module-K/ or DIR/view-K/, with view.json)");
  render_cmd->add_option(
      "--environment", render.environment,
      "What lights the scenes: an equirectangular HDR or EXR (prefiltered at load), or builtin:studio (the default)");
  render_cmd->add_option("--display", render.display,
                         "Light field display file (TOML, see board/displays): render every optical module or quilt view; "
                         "-o writes the montage of the modules or the quilt, --size is ignored");
  render_cmd->add_option("--modules-dir", render.modules_dir,
                         "With --display: one PNG per module (module-K.png) or view (view-K.png)");
  render_cmd->add_option("--native", render.native_output, "With a quilt --display: the interleaved native panel image (PNG)");
  render_cmd->add_option("--shader-cache", render.shader_cache, shader_cache_help);
  render_cmd->add_flag("--view-probe", render.view_probe,
                       "With --display: draw view k as the flat grey (k, k, k) instead of the scene, to check the interleave");

  std::string info_platform = "auto";
  auto* info_cmd = cli.add_subcommand("info", "Print the platform, GL renderer, version and the extensions used");
  info_cmd->add_option("--platform", info_platform, "GL platform: " + platform::names_text())
      ->check(CLI::IsMember(platform::names()))
      ->capture_default_str();
  std::string info_shader_cache;
  info_cmd->add_option("--shader-cache", info_shader_cache, shader_cache_help);

  hal::HalTestOptions hal_test;
  auto* hal_cmd = cli.add_subcommand(
      "hal-test", "Wiring check for a new board: print button events, cycle the LEDs, capture a frame and save it");
  hal_cmd->add_option("--board", hal_test.board_file, "Board description (TOML, see board/); without it, a built-in mock board");
  hal_cmd->add_option("--hal", hal_test.backend, "Hardware backend: linux or mock; default linux with --board, mock without")
      ->check(CLI::IsMember(hal::backend_names()));
  hal_cmd->add_option("--capture", hal_test.capture_path, "Where to save the captured frame")->capture_default_str();
  hal_cmd->add_option("--duration", hal_test.duration_s, "Seconds to listen to buttons and cycle LEDs")
      ->check(CLI::Range(0.0, 3600.0))
      ->capture_default_str();

  std::vector<std::string> check_scenes;
  auto* check_cmd = cli.add_subcommand(
      "check", "Load scenes as play does, without GL, and say for each whether it plays (exit 1 if any is refused)");
  check_cmd->add_option("scenes", check_scenes, "Scenes to check (.gltf, .glb, builtin:NAME)")->required();

  app::CtlOptions ctl;
  ctl.control = std::string(control::kDefaultPath);
  auto* ctl_cmd =
      cli.add_subcommand("ctl",
                         "Send one command to a running player through its control socket and print its reply (exit 0: done, 1: "
                         "refused, 2: no player to ask)");
  ctl_cmd->add_option("command", ctl.words, "One of " + control::verbs_text())->required();
  ctl_cmd->add_option("--control", ctl.control, "The player's control socket")->capture_default_str();
  ctl_cmd->add_option("--timeout", ctl.timeout_s, "Seconds to wait for the reply")->capture_default_str();

  app::ContentOptions content_options;
  content_options.root = std::string(content::kDefaultRoot);
  auto* content_cmd = cli.add_subcommand(
      "content", "Install content bundles as versions, checked before they play; roll back; list (docs/content.md)");
  content_cmd->require_subcommand(1);
  auto* install_cmd = content_cmd->add_subcommand(
      "install", "Check a bundle (a folder or .tar with playlist.toml) with the player's loader, then make it current");
  install_cmd->add_option("source", content_options.source, "The bundle: a folder, or a .tar (.gz, .xz, .zst) of one")
      ->required();
  install_cmd->add_option("--keep", content_options.keep, "Earlier versions kept besides the current one")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  install_cmd->add_option("--max-size", content_options.max_size, "The bundle's size budget, unpacked (e.g. 500M, 4G)")
      ->capture_default_str();
  auto* take_cmd = content_cmd->add_subcommand(
      "take", "Install every bundle (.tar, .tar.gz, ...) waiting in INBOX, oldest first, removing each whatever the outcome");
  take_cmd->add_option("inbox", content_options.source, "The folder bundles arrive in")->required();
  take_cmd->add_option("--keep", content_options.keep, "Earlier versions kept besides the current one")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  take_cmd->add_option("--max-size", content_options.max_size, "Each bundle's size budget, unpacked (e.g. 500M, 4G)")
      ->capture_default_str();
  content_cmd->add_subcommand("rollback", "Make the version installed before the current one current again");
  content_cmd->add_subcommand("list", "The installed versions, oldest first; * marks the current one");
  for (CLI::App* sub : content_cmd->get_subcommands({}))
    sub->add_option("--root", content_options.root, "The content root (versions/ and the link current)")->capture_default_str();

  fleet::Options fleet_options;
  auto* fleet_cmd = cli.add_subcommand(
      "fleet",
      "Carry this player's status to an MQTT broker (with Home Assistant discovery) and the broker's commands to its control "
      "socket, until stopped (docs/fleet.md)");
  fleet_cmd->add_option("--config", fleet_options.config, "The agent's configuration (TOML)")->capture_default_str();
  fleet_cmd->add_flag("--check", fleet_options.check,
                      "Check the configuration (with its password and CA files), print what the agent would do, and exit");
  fleet_cmd->add_flag("--remove", fleet_options.remove,
                      "Withdraw this player from the broker (Home Assistant's device, state, availability) and exit");
  fleet_cmd
      ->add_option("--duration", fleet_options.duration_s,
                   "Stop after this many seconds (0: run until SIGTERM or SIGINT; with --remove: how long to try)")
      ->check(CLI::Range(0.0, 1e7))
      ->capture_default_str();

  app::PlayOptions play;
  std::string play_size = "1024x768";
  auto* play_cmd =
      cli.add_subcommand("play", "Play a playlist (TOML) or scenes in a loop, kiosk style, until stopped (the default command)");
  play_cmd->add_option("inputs", play.inputs, "One playlist (.toml), or scenes (.gltf, .glb, builtin:NAME); none: builtin:demo");
  play_cmd->add_option(
      "--environment", play.environment,
      "What lights the scenes: an equirectangular HDR or EXR (prefiltered at load), or builtin:studio (the default)"
      " for items whose playlist entry names no environment");
  play_cmd->add_option("--content", play.content_root,
                       "Folder the playlist's files must stay inside (default: the playlist's folder)");
  play_cmd->add_option("--duration", play.duration_s, "Scenes named on the command line: seconds each")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  play_cmd->add_option("--period", play.period_s, "Scenes named on the command line: turntable seconds per turn")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  play_cmd->add_option("--platform", play.platform, "GL platform: " + platform::names_text())
      ->check(CLI::IsMember(platform::names()))
      ->capture_default_str();
  play_cmd->add_option("--size", play_size, "Surface size WxH (headless platforms; a window's initial size)")
      ->capture_default_str();
  play_cmd->add_flag("--fullscreen", play.fullscreen, "Start the window fullscreen (F11 toggles)");
  play_cmd->add_option(
      "--drm-device", play.drm_device,
      "kms: the DRM node (default: the first with KMS and a connected display; card numbers change between boots)");
  play_cmd
      ->add_option("--drm-connector", play.drm_connector,
                   "kms: the connector, by name (HDMI-A-1, DSI-1, ...); auto: the first connected; help: list them and exit")
      ->capture_default_str();
  play_cmd->add_option("--drm-mode", play.drm_mode, "kms: preferred, highest, or WxH[@R] (e.g. 1920x1080@60)")
      ->capture_default_str();
  play_cmd
      ->add_option("--drm-atomic", play.drm_atomic, "kms: auto (atomic modesetting where the driver offers it) or no (legacy)")
      ->check(CLI::IsMember({"auto", "no"}))
      ->capture_default_str();
  play_cmd->add_option(
      "--snapshot", play.snapshot,
      "With --frames N: write frame N-1 as drawn onto the surface (after rotation) to FILE (PNG), before it is presented");
  play_cmd
      ->add_option("--rotation", play.rotation,
                   "Turn frames 0, 90, 180 or 270 degrees clockwise for a display mounted turned (default: the board file's "
                   "[display] rotation, else 0); the renderer turns them, not the display controller")
      ->check(CLI::IsMember({0, 90, 180, 270}));
  play_cmd->add_option("--drm-writeback", play.drm_writeback,
                       "kms: at exit, write what the display shows to FILE (PNG), read back through the DRM writeback connector");
  play_cmd->add_option("--overlay", play.overlay, "Panel with the status LEDs and the state: on, off, or auto (on in a window)")
      ->check(CLI::IsMember({"auto", "on", "off"}))
      ->capture_default_str();
  play_cmd->add_option("--frames", play.frames, "Stop after N frames (0: run until SIGTERM or SIGINT)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  play_cmd->add_option("--out", play.out_dir, "Write every frame as DIR/frame-NNNNNN.png");
  play_cmd
      ->add_option(
          "--fps", play.fps,
          "Pace frames and the playlist clock at F per second (default: as fast as possible, the clock advancing 1/30 s a frame)")
      ->check(CLI::NonNegativeNumber);
  play_cmd->add_option("--board", play.board_file, "Board description (TOML, see board/); without it, a built-in mock board");
  play_cmd->add_option("--hal", play.hal, "Hardware backend: linux or mock; default linux with --board, mock without")
      ->check(CLI::IsMember(hal::backend_names()));
  play_cmd->add_option("--buttons-script", play.buttons_script, "Mock buttons: lines of `t_ms BUTTON press|release`");
  play_cmd->add_option("--status", play.status_file, "Status file (JSON, replaced atomically); default the board's status_file");
  play_cmd->add_option("--metrics", play.metrics_file,
                       "Write Prometheus metrics to FILE (node_exporter's textfile collector: name it *.prom) at every "
                       "status update, replaced whole; default the board's metrics_file");
  play_cmd->add_option("--control", play.control,
                       "Listen for commands (player ctl) on the AF_UNIX socket PATH; default the board's control (none "
                       "without it); off: none");
  play_cmd->add_option("--log", play.log_file,
                       "Write a line per frame: item, state, LED patterns, button actions, frame time, resident memory");
  play_cmd->add_option("--camera-script", play.camera_script, "Mock camera: lines of `t_ms unplug|replug` (with --hal mock)");
  play_cmd->add_option("--shader-cache", play.shader_cache, shader_cache_help);
  play_cmd
      ->add_option_function<std::string>(
          "--start-time",
          [&play](const std::string& text) {
            std::string error;
            if (!app::parse_start_time(text, play.start_time_s, error)) throw CLI::ValidationError(error);
          },
          "Play as if the wall clock read TIME at the start (2026-12-07T17:59:30Z, with an offset, or Unix seconds): "
          "previews the board's opening hours and wallclock playlists; default now")
      ->type_name("TIME");
  SettingOptions play_settings;
  play_settings.add_to(*play_cmd, play.settings);
  cli.require_subcommand(0, 1);

  CLI11_PARSE(cli, argc, argv);

  if (cli.get_subcommands().empty() || play_cmd->parsed()) {
    if (play.drm_connector == "help") {
      platform::Options options;
      options.drm_device = play.drm_device;
      std::string text, error;
      if (!platform::describe_kms_outputs(options, text, error)) {
        std::cerr << "error: " << error << "\n";
        return 2;
      }
      std::cout << text;
      return 0;
    }
    if (!play.snapshot.empty() && play.frames == 0) {
      std::cerr << "error: --snapshot: expected --frames N as well (the snapshot is of frame N-1)\n";
      return 2;
    }
    if (!apply_frame_options(play_size, play.width, play.height, play_settings, play.settings)) return 2;
    return app::run_play(play, std::cout, std::cerr);
  }

  if (hal_cmd->parsed()) return hal::run_hal_test(hal_test, std::cout);

  if (render_cmd->parsed()) {
    if (!apply_frame_options(size, render.frame.width, render.frame.height, render_settings, render.frame)) return 2;
    for (const auto& [key, value] : render_settings.values) render.estimator_given |= key == "estimator" && !value.empty();
    return app::run_render(render, std::cout, std::cerr);
  }
  if (info_cmd->parsed()) return app::run_info(info_platform, info_shader_cache, std::cout, std::cerr);
  if (check_cmd->parsed()) return app::run_check(check_scenes, std::cout, std::cerr);
  if (ctl_cmd->parsed()) return app::run_ctl(ctl, std::cout, std::cerr);
  if (content_cmd->parsed()) {
    content_options.action = content_cmd->get_subcommands().front()->get_name();
    return app::run_content(content_options, std::cout, std::cerr);
  }
  if (fleet_cmd->parsed()) return fleet::run_fleet(fleet_options, PLAYER_VERSION, std::cout, std::cerr);
  return 2;
}
