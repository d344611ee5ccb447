// The player's command line: a thin layer over the app library.
#include "app/render_command.h"
#include "hal/hal_test.h"
#include "platform/platform.h"
#include "scene/procedural.h"
#include "ssao/params.h"

#include <CLI/CLI.hpp>

#include <iostream>
#include <map>

namespace {

template <typename Enum>
std::map<std::string, Enum> choices(std::initializer_list<std::pair<const char*, Enum>> list) {
  std::map<std::string, Enum> map;
  for (const auto& [text, value] : list) map.emplace(text, value);
  return map;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App cli{"player: a kiosk glTF player with screen-space ambient occlusion on OpenGL ES 3.1 compute"};
  cli.require_subcommand(1);

  app::RenderOptions render;
  std::string size = "1024x768";
  std::string ao = "on", prepass = "auto";
  auto* render_cmd = cli.add_subcommand("render", "Render one frame of SCENE to a PNG and print per-pass GPU times");
  std::string builtins;
  for (const std::string& name : scene::builtin_names()) builtins += " builtin:" + name;
  render_cmd->add_option("scene", render.scene, "A .gltf or .glb file, or a built-in scene:" + builtins)->required();
  render_cmd->add_option("-o,--output", render.output, "PNG file to write")->required();
  render_cmd->add_option("--size", size, "Image size WxH")->capture_default_str();
  render_cmd->add_option("--azimuth", render.framing.azimuth_deg, "Camera azimuth about +Y in degrees")->capture_default_str();
  render_cmd->add_option("--elevation", render.framing.elevation_deg, "Camera elevation in degrees")
      ->check(CLI::Range(-90.0, 90.0))->capture_default_str();
  render_cmd->add_option("--distance", render.framing.distance, "Camera distance as a multiple of the distance that just fits the scene")
      ->check(CLI::PositiveNumber)->capture_default_str();
  render_cmd->add_option("--ao", ao, "Ambient occlusion on or off")->check(CLI::IsMember({"on", "off"}))->capture_default_str();
  render_cmd->add_option("--estimator", render.frame.ao_settings.estimator,
                         "AO estimator: sphere (the paper, Mittring), hemisphere (cosine-weighted about the normal), horizon (GTAO)")
      ->transform(CLI::CheckedTransformer(choices<ssao::Estimator>({{"sphere", ssao::Estimator::sphere},
                                                                    {"hemisphere", ssao::Estimator::hemisphere},
                                                                    {"horizon", ssao::Estimator::horizon}})))
      ->default_str(std::string(ssao::name(render.frame.ao_settings.estimator)));
  const auto on_off = [](bool on) { return std::string(on ? "on" : "off"); };
  std::string resolution = render.frame.ao_settings.half_resolution ? "half" : "full";
  std::string depth_chain = on_off(render.frame.ao_settings.depth_chain), skip_radii = on_off(render.frame.ao_settings.skip_radii),
              reuse_ao = on_off(render.frame.reuse_static_ao);
  render_cmd->add_option("--reuse-ao", reuse_ao, "Keep the last frame's AO while camera and scene stand still (off: recompute every frame, for timing)")
      ->check(CLI::IsMember({"on", "off"}))->capture_default_str();
  render_cmd->add_option("--resolution", resolution, "AO resolution: full, or half with depth-aware upsampling")
      ->check(CLI::IsMember({"full", "half"}))->capture_default_str();
  render_cmd->add_option("--depth-chain", depth_chain, "Large radii read a downsampled depth chain")
      ->check(CLI::IsMember({"on", "off"}))->capture_default_str();
  render_cmd->add_option("--skip-radii", skip_radii, "Skip radii under a quarter pixel or beyond the scene's size, per frame")
      ->check(CLI::IsMember({"on", "off"}))->capture_default_str();
  render_cmd->add_option("--samples", render.frame.ao_settings.samples, "AO samples per radius (horizon: taps per pixel, 8 per slice)")
      ->check(CLI::Range(1, SSAO_MAX_SAMPLES))->capture_default_str();
  render_cmd->add_option("--radii", render.frame.ao_settings.radii, "AO radii (multi-resolution, merged by max)")
      ->check(CLI::Range(1, SSAO_MAX_RADII))->capture_default_str();
  render_cmd->add_option("--radius", render.frame.radius, "Largest AO radius in scene units (default: a tenth of the scene's bounding radius)")
      ->check(CLI::NonNegativeNumber);
  render_cmd->add_option("--pattern", render.frame.ao_settings.pattern, "Sample pattern")
      ->transform(CLI::CheckedTransformer(choices<ssao::Pattern>({{"random", ssao::Pattern::random},
                                                                  {"jittered", ssao::Pattern::jittered},
                                                                  {"latin", ssao::Pattern::latin},
                                                                  {"poisson", ssao::Pattern::poisson}})))
      ->default_str(std::string(ssao::name(render.frame.ao_settings.pattern)));
  render_cmd->add_option("--blur", render.frame.blur.mode, "AO blur")
      ->transform(CLI::CheckedTransformer(choices<ssao::Blur>({{"gaussian", ssao::Blur::gaussian},
                                                               {"bilateral", ssao::Blur::bilateral},
                                                               {"off", ssao::Blur::off}})))
      ->default_str(std::string(ssao::name(render.frame.blur.mode)));
  render_cmd->add_option("--view", render.frame.view, "What to show")
      ->transform(CLI::CheckedTransformer(choices<render::View>({{"color", render::View::color},
                                                                 {"ao", render::View::ao},
                                                                 {"normal", render::View::normal},
                                                                 {"depth", render::View::depth}})))
      ->default_str(std::string(render::name(render.frame.view)));
  render_cmd->add_option("--prepass", prepass, "Depth prepass before the G-buffer: on, off, or auto (measure both, keep the faster)")
      ->check(CLI::IsMember({"on", "off", "auto"}))->capture_default_str();
  render_cmd->add_option("--platform", render.platform, "GL platform: egl (headless EGL), osmesa, or auto (egl, then osmesa)")
      ->check(CLI::IsMember(platform::names()))->capture_default_str();
  render_cmd->add_option("--frames", render.frames, "Frames to render; times are the median of all but the first")
      ->check(CLI::Range(1, 100000))->capture_default_str();
  render_cmd->add_option("--dump", render.dump_dir,
                         "Write float EXRs (raw and blurred AO, world position, normal, linear depth) and camera.json to DIR");

  std::string info_platform = "auto";
  auto* info_cmd = cli.add_subcommand("info", "Print the platform, GL renderer, version and the extensions used");
  info_cmd->add_option("--platform", info_platform, "GL platform: egl, osmesa or auto")
      ->check(CLI::IsMember(platform::names()))->capture_default_str();

  hal::HalTestOptions hal_test;
  auto* hal_cmd = cli.add_subcommand("hal-test",
                                     "Wiring check for a new board: print button events, cycle the LEDs, capture a frame and save it");
  hal_cmd->add_option("--board", hal_test.board_file, "Board description (TOML, see board/); without it, a built-in mock board");
  hal_cmd->add_option("--hal", hal_test.backend, "Hardware backend: linux or mock; default linux with --board, mock without")
      ->check(CLI::IsMember({"linux", "mock"}));
  hal_cmd->add_option("--capture", hal_test.capture_path, "Where to save the captured frame")->capture_default_str();
  hal_cmd->add_option("--duration", hal_test.duration_s, "Seconds to listen to buttons and cycle LEDs")
      ->check(CLI::Range(0.0, 3600.0))->capture_default_str();

  CLI11_PARSE(cli, argc, argv);

  if (hal_cmd->parsed()) return hal::run_hal_test(hal_test, std::cout);

  if (render_cmd->parsed()) {
    int width = 0, height = 0;
    char separator = 0;
    std::istringstream size_text(size);
    if (!(size_text >> width >> separator >> height) || separator != 'x' || width < 1 || height < 1 || !size_text.eof()) {
      std::cerr << "error: --size: '" << size << "' is not WxH with positive integers (e.g. 1024x768)\n";
      return 2;
    }
    render.frame.width = width;
    render.frame.height = height;
    render.frame.ao = ao == "on";
    render.frame.prepass = prepass == "on" ? render::Prepass::on : prepass == "off" ? render::Prepass::off : render::Prepass::automatic;
    render.frame.ao_settings.half_resolution = resolution == "half";
    render.frame.ao_settings.depth_chain = depth_chain == "on";
    render.frame.ao_settings.skip_radii = skip_radii == "on";
    render.frame.reuse_static_ao = reuse_ao == "on";
    return app::run_render(render, std::cout, std::cerr);
  }
  if (info_cmd->parsed()) return app::run_info(info_platform, std::cout, std::cerr);
  return 2;
}
