// aobench: AO run time against error. For each scene and view it renders the G-buffer once, traces
// the two references at exactly those surface points (aoref), then renders every configuration,
// timing its AO passes with GPU timer queries and measuring its error against the matching reference.
// Writes a CSV (a row per scene, view and configuration) and a PNG chart with the Pareto front.
#include "aoref/metrics.h"
#include "aoref/ray_scene.h"
#include "aoref/reference.h"
#include "chart.h"
#include "configs.h"
#include "ghosting.h"
#include "gl/caps.h"
#include "gl/gl_api.h"
#include "gl/session.h"
#include "platform/platform.h"
#include "render/renderer.h"
#include "render/settings.h"
#include "scene/load.h"

#include <CLI/CLI.hpp>

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>

namespace {

// The settings columns of the CSV, in the codec's names.
constexpr const char* kCsvSettings[] = {"estimator",
                                        "samples",
                                        "steps",
                                        "radii",
                                        "pattern",
                                        "blur",
                                        "resolution",
                                        "depth-chain",
                                        "skip-radii",
                                        "skip-background",
                                        "untextured-variant",
                                        "reuse-ao",
                                        "temporal",
                                        "prepass"};

namespace fs = std::filesystem;

struct Options {
  std::vector<std::string> scenes;
  std::string size = "1024x768";
  int frames = 5;
  int views = 3;
  double distance = 1.0;
  int rays = 256;
  std::vector<std::string> configs;
  std::string sweep;  // "", "quick", "full" or "ablation"
  std::string platform = "auto";
  std::string csv = "out/aobench.csv";
  std::string chart = "out/aobench.png";
  std::string noise_chart = "out/aobench-noise.png";
  bool temporal = true;  // the accumulation columns (still camera and turntable)
  bool ghosting = false;
  aobench::GhostingOptions ghost;
};

// The turntable of the temporal columns: 10 degrees per second at 30 frames per second.
constexpr double kTurntableDegreesPerFrame = 10.0 / 30.0;
constexpr int kAccumulatedFrames[] = {1, 4, 16};

// Converts a bottom-up (GL) image to the top-down layout of aoref images.
aoref::Image top_down(const std::vector<float>& values, int width, int height, int channels) {
  aoref::Image image(width, height, channels);
  const size_t row = static_cast<size_t>(width) * static_cast<size_t>(channels);
  for (int y = 0; y < height; ++y)
    std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(row * static_cast<size_t>(height - 1 - y)), row,
                image.values.begin() + static_cast<std::ptrdiff_t>(row * static_cast<size_t>(y)));
  return image;
}

aoref::Image ao_image(const std::vector<glm::vec2>& ao, int width, int height, bool sphere_to_hemisphere) {
  std::vector<float> values(ao.size());
  // The sphere estimator counts the half of its sphere below a plane as hidden: 0.5 on an open face.
  // Against the hemisphere reference its value maps to the hidden share of the upper half, 2f - 1.
  for (size_t i = 0; i < ao.size(); ++i)
    values[i] = sphere_to_hemisphere ? std::clamp(2.0f * ao[i].x - 1.0f, 0.0f, 1.0f) : ao[i].x;
  return top_down(values, width, height, 1);
}

aoref::Image merge_radii(const aoref::ReferenceResult& sphere, int radii) {
  aoref::Image merged = sphere.per_radius.at(0);
  for (int k = 1; k < radii && k < static_cast<int>(sphere.per_radius.size()); ++k)
    for (size_t i = 0; i < merged.values.size(); ++i)
      merged.values[i] = std::max(merged.values[i], sphere.per_radius[static_cast<size_t>(k)].values[i]);
  return merged;
}

void progress_bar(const std::string& what, int done, int total) {
  if (!isatty(STDERR_FILENO)) return;
  const int width = 30, filled = total > 0 ? done * width / total : width;
  std::cerr << "\r  " << what << " [" << std::string(static_cast<size_t>(filled), '#')
            << std::string(static_cast<size_t>(width - filled), '.') << "] " << done << "/" << total << std::flush;
  if (done >= total) std::cerr << "\n";
}

struct Row {
  std::string scene;
  int view = 0;
  const aobench::Config* config = nullptr;
  double time_ms = 0.0;   // the AO passes (depth chain, SSAO, blur, upsampling)
  double frame_ms = 0.0;  // every pass of the frame
  aoref::Metrics own, near_field;
  std::string reference;
  // With temporal accumulation (the configuration with temporal=on, reuse-ao=off): MAE against the
  // near-field reference after kAccumulatedFrames frames of a still camera and of a turntable that
  // ends at this view; and the turntable's last step's change of AO at matched pixels, minus the
  // reference's own change there (NaN when the columns are off).
  double still_mae[3] = {}, turn_mae[3] = {};
  double still_noise = 0.0, turn_noise = 0.0;  // the error's high-frequency noise after 16 frames
  double instability = 0.0;
};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0.0 : values[values.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App cli{"aobench: AO run time against error over scenes, views and configurations"};
  cli.add_option("--scene", options.scenes,
                 "Scenes (.gltf/.glb or builtin:NAME); default: builtin:demo and ../shared/scenes/*.glb");
  cli.add_option("--size", options.size, "Image size WxH")->capture_default_str();
  cli.add_option("--frames", options.frames, "Timed frames per configuration (after one warm-up)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cli.add_option("--views", options.views, "Views per scene (azimuths spread round the scene)")
      ->check(CLI::Range(1, 12))
      ->capture_default_str();
  cli.add_option(
         "--distance", options.distance,
         "Camera distance as a multiple of the distance at which the scene just fits (far views shrink the radii on screen)")
      ->check(CLI::Range(0.2, 100.0))
      ->capture_default_str();
  cli.add_option("--rays", options.rays, "Reference rays per pixel (per radius for the sphere reference)")
      ->check(CLI::Range(8, 1 << 16))
      ->capture_default_str();
  cli.add_option("--config", options.configs,
                 "Configurations: paper, default, or key=value,... (see docs/ao.md); default: paper and default");
  cli.add_option("--sweep", options.sweep,
                 "Add a grid: quick, full, or ablation (the default with each saving turned off in turn)")
      ->check(CLI::IsMember({"quick", "full", "ablation"}));
  cli.add_option("--platform", options.platform, "GL platform: auto, egl or osmesa")
      ->check(CLI::IsMember(platform::names()))
      ->capture_default_str();
  cli.add_option("-o,--csv", options.csv, "CSV output")->capture_default_str();
  cli.add_option("--chart", options.chart, "PNG chart output: time against MAE")->capture_default_str();
  cli.add_option("--noise-chart", options.noise_chart, "PNG chart output: time against the error's high-frequency noise")
      ->capture_default_str();
  cli.add_flag("!--no-temporal", options.temporal,
               "Leave out the temporal columns (error after 1, 4 and 16 accumulated frames, still and turntable; instability)");
  cli.add_flag("--ghosting", options.ghosting,
               "Instead: temporal AO on animated scenes (default: the animated samples in ../shared/samples), its error over "
               "moving pixels against one frame's, with and without motion vectors (docs/ao.md, AO of moving parts)");
  cli.add_option("--ghosting-frames", options.ghost.frames, "--ghosting: frames played up to each measured pose")
      ->check(CLI::Range(2, 255))
      ->capture_default_str();
  cli.add_option("--ghosting-poses", options.ghost.poses, "--ghosting: poses measured per scene, spread over its loop")
      ->check(CLI::Range(1, 32))
      ->capture_default_str();
  CLI11_PARSE(cli, argc, argv);

  int width = 0, height = 0;
  char separator = 0;
  std::istringstream size_text(options.size);
  if (!(size_text >> width >> separator >> height) || separator != 'x' || width < 8 || height < 8) {
    std::cerr << "error: --size: '" << options.size << "' is not WxH (e.g. 1024x768)\n";
    return 2;
  }
  if (options.ghosting) {
    options.ghost.scenes = options.scenes;
    options.ghost.width = width;
    options.ghost.height = height;
    options.ghost.platform = options.platform;
    return aobench::run_ghosting(options.ghost);
  }
  if (options.scenes.empty()) {
    options.scenes.push_back("builtin:demo");
    std::vector<std::string> shared;
    if (fs::is_directory("../shared/scenes"))
      for (const auto& entry : fs::directory_iterator("../shared/scenes"))
        if (entry.path().extension() == ".glb") shared.push_back(entry.path().string());
    std::sort(shared.begin(), shared.end());
    options.scenes.insert(options.scenes.end(), shared.begin(), shared.end());
  }

  std::vector<aobench::Config> configs;
  std::string error;
  if (options.configs.empty() && options.sweep != "ablation") options.configs = {"paper", "default"};
  for (const std::string& text : options.configs) {
    auto config = aobench::parse_config(text, error);
    if (!config) {
      std::cerr << "error: " << error << "\n";
      return 2;
    }
    configs.push_back(*config);
  }
  if (!options.sweep.empty()) {
    auto grid = aobench::sweep(options.sweep);
    configs.insert(configs.end(), grid.begin(), grid.end());
  }
  for (aobench::Config& config : configs) {
    config.settings.width = width;
    config.settings.height = height;
  }

  platform::Options platform_options;
  platform_options.name = options.platform;
  platform_options.size = {width, height};
  const auto session = gl::Session::open(platform_options, error);
  if (!session) {
    std::cerr << "error: " << error << "\n";
    return 1;
  }
  const platform::Platform& platform = session->platform();
  const gl::Caps& caps = session->caps();
  std::cout << "aobench: " << configs.size() << " configurations x " << options.scenes.size() << " scenes x " << options.views
            << " views at " << width << "x" << height << " on " << platform.name() << " (" << caps.renderer << ")"
            << (caps.timer_query ? ", GPU timer queries" : ", CPU clock around glFinish") << "\n";

  fs::create_directories(fs::path(options.csv).parent_path().empty() ? "." : fs::path(options.csv).parent_path());
  std::ofstream csv(options.csv);
  if (!csv) {
    std::cerr << "error: " << options.csv << ": cannot write\n";
    return 1;
  }
  csv << "scene,view,config";
  for (const char* key : kCsvSettings) csv << ',' << key;
  csv << ","
         "time_ms,raster_ms,frame_ms,reference,mae,rmse,ssim,edge_mae,mae_near_field,rmse_near_field,ssim_near_field,"
         "bias_near_field,noise_near_field,mae_still_1,mae_still_4,mae_still_16,mae_turn_1,mae_turn_4,mae_turn_16,"
         "noise_still_16,noise_turn_16,instability\n";
  std::vector<Row> rows;

  for (const std::string& scene_spec : options.scenes) {
    scene::Scene scene;
    if (!scene::load(scene_spec, scene, error, std::cerr)) {
      std::cerr << "error: " << error << "\n";
      return 1;
    }
    aoref::RayScene rays;
    if (!rays.build(scene, error)) {
      std::cerr << "error: " << scene_spec << ": " << error << "\n";
      return 1;
    }
    render::Renderer renderer;
    render::FrameSettings base = configs.front().settings;
    const render::PresentTarget target{platform.framebuffer(), 0, 0, platform.srgb_framebuffer()};
    if (!renderer.init(*session, target, error) || !renderer.upload(scene, error) || !renderer.configure(base, error)) {
      std::cerr << "error: " << scene_spec << ": " << error << "\n";
      return 1;
    }
    for (int view_index = 0; view_index < options.views; ++view_index) {
      scene::Framing framing;
      framing.azimuth_deg = 30.0 + 360.0 * view_index / options.views;
      framing.elevation_deg = 25.0;
      framing.distance = options.distance;
      const scene::Camera camera = scene::frame(scene.bounds, framing, width, height);
      // The turntable's previous frame, for the instability column: its own surface and reference.
      scene::Framing previous_framing = framing;
      previous_framing.azimuth_deg -= kTurntableDegreesPerFrame;
      const scene::Camera previous_camera = scene::frame(scene.bounds, previous_framing, width, height);
      renderer.render(camera);
      const render::WorldSurface surface = render::read_world_surface(renderer.targets(), render::view_of(camera));
      aoref::View view;
      view.eye = camera.eye;
      for (int k = 0; k < SSAO_MAX_RADII; ++k) view.radii.push_back(renderer.base_radius() * std::ldexp(1.0, -k));
      view.position = top_down(surface.position, width, height, 4);
      view.normal = top_down(surface.normal, width, height, 4);
      const aoref::Image depth = top_down(surface.depth, width, height, 1);
      std::cout << scene_spec << ", view " << view_index << ": tracing references (" << options.rays << " rays per pixel)\n";
      aoref::ReferenceSettings reference_settings;
      reference_settings.rays = options.rays;
      reference_settings.progress = [](int done, int total) { progress_bar("rows", done, total); };
      aoref::ReferenceResult near_field, sphere;
      reference_settings.reference = aoref::Reference::near_field;
      if (!aoref::compute_reference(rays, view, reference_settings, near_field, error)) {
        std::cerr << "error: " << error << "\n";
        return 1;
      }
      reference_settings.reference = aoref::Reference::sphere;
      if (!aoref::compute_reference(rays, view, reference_settings, sphere, error)) {
        std::cerr << "error: " << error << "\n";
        return 1;
      }
      aoref::ReferenceResult previous_near_field;
      aoref::Image previous_positions, positions = view.position;
      if (options.temporal) {
        renderer.render(previous_camera);
        const render::WorldSurface previous = render::read_world_surface(renderer.targets(), render::view_of(previous_camera));
        aoref::View previous_view = view;
        previous_view.eye = previous_camera.eye;
        previous_view.position = top_down(previous.position, width, height, 4);
        previous_view.normal = top_down(previous.normal, width, height, 4);
        previous_positions = previous_view.position;
        reference_settings.reference = aoref::Reference::near_field;
        std::cout << "  tracing the turntable's previous frame\n";
        if (!aoref::compute_reference(rays, previous_view, reference_settings, previous_near_field, error)) {
          std::cerr << "error: " << error << "\n";
          return 1;
        }
      }
      std::cout << "  reference noise: near-field mean standard error " << near_field.mean_standard_error << " (max "
                << near_field.max_standard_error << "), sphere " << sphere.mean_standard_error << " (max "
                << sphere.max_standard_error << ")\n";
      for (size_t c = 0; c < configs.size(); ++c) {
        const aobench::Config& config = configs[c];
        if (!renderer.configure(config.settings, error)) {
          std::cerr << "error: " << config.name << ": " << error << "\n";
          return 1;
        }
        // Frame 0 warms up (and, with reuse on, computes the AO the timed frames keep).
        std::vector<double> times, raster_times, frame_times;
        for (int frame = 0; frame <= options.frames; ++frame) {
          renderer.render(camera);
          const render::PassTimes pass = renderer.collect_times();
          double ao_ms = 0.0, frame_ms = 0.0;
          // Upsampling happens inside the present pass, which also shades: it is in frame_ms, not here.
          for (render::Pass p : {render::Pass::depth_chain, render::Pass::ssao, render::Pass::temporal, render::Pass::blur_h,
                                 render::Pass::blur_v})
            ao_ms += std::max(0.0, pass[p]);
          for (double ms : pass.ms) frame_ms += std::max(0.0, ms);
          if (frame > 0) {
            times.push_back(ao_ms);
            raster_times.push_back(std::max(0.0, pass[render::Pass::depth_prepass]) + std::max(0.0, pass[render::Pass::gbuffer]));
            frame_times.push_back(frame_ms);
          }
        }
        const bool is_sphere = config.settings.ao_settings.estimator == ssao::Estimator::sphere;
        const auto estimate = renderer.read_ao_final();
        Row row;
        row.scene = scene_spec;
        row.view = view_index;
        row.config = &config;
        row.time_ms = median(times);
        row.frame_ms = median(frame_times);
        row.reference = is_sphere ? "sphere" : "near-field";
        row.own = aoref::compare(ao_image(estimate, width, height, false),
                                 is_sphere ? merge_radii(sphere, config.settings.ao_settings.radii) : near_field.ao, depth);
        row.near_field = aoref::compare(ao_image(estimate, width, height, is_sphere), near_field.ao, depth);
        for (int n = 0; n < 3; ++n) row.still_mae[n] = row.turn_mae[n] = std::numeric_limits<double>::quiet_NaN();
        row.still_noise = row.turn_noise = std::numeric_limits<double>::quiet_NaN();
        row.instability = std::numeric_limits<double>::quiet_NaN();
        if (options.temporal) {
          render::FrameSettings accumulating = config.settings;
          accumulating.temporal = true;
          accumulating.reuse_static_ao = false;
          auto metrics_now = [&] {
            return aoref::compare(ao_image(renderer.read_ao_final(), width, height, is_sphere), near_field.ao, depth);
          };
          for (int n = 0; n < 3; ++n) {
            const int frames = kAccumulatedFrames[n];
            // Still: the same camera N times. Turntable: N frames that end at this view.
            for (bool turning : {false, true}) {
              if (!renderer.configure(accumulating, error)) {
                std::cerr << "error: " << config.name << ": " << error << "\n";
                return 1;
              }
              std::vector<glm::vec2> before;
              for (int frame = 0; frame < frames; ++frame) {
                scene::Framing at = framing;
                if (turning) at.azimuth_deg -= kTurntableDegreesPerFrame * (frames - 1 - frame);
                if (turning && frame == frames - 1 && frames > 1) before = renderer.read_ao_final();
                renderer.render(scene::frame(scene.bounds, at, width, height));
              }
              const aoref::Metrics accumulated = metrics_now();
              (turning ? row.turn_mae : row.still_mae)[n] = accumulated.mae;
              if (frames == kAccumulatedFrames[2]) (turning ? row.turn_noise : row.still_noise) = accumulated.noise;
              if (turning && frames == kAccumulatedFrames[2]) {
                const glm::dmat4 previous_view_projection = previous_camera.projection() * previous_camera.view();
                const std::vector<int64_t> match =
                    aoref::match_previous(positions, previous_positions, previous_view_projection, previous_camera.eye);
                const aoref::Image estimate_now = ao_image(renderer.read_ao_final(), width, height, is_sphere);
                const aoref::Image estimate_before = ao_image(before, width, height, is_sphere);
                row.instability = aoref::mean_change(estimate_now, estimate_before, match) -
                                  aoref::mean_change(near_field.ao, previous_near_field.ao, match);
              }
            }
          }
        }
        csv << '"' << scene_spec << "\"," << view_index << ",\"" << config.name << "\"";
        for (const char* key : kCsvSettings) csv << ',' << render::setting_value(config.settings, key);
        csv << ',' << row.time_ms << ',' << median(raster_times) << ',' << row.frame_ms << ',' << row.reference << ','
            << row.own.mae << ',' << row.own.rmse << ',' << row.own.ssim << ',' << row.own.edge_mae << ',' << row.near_field.mae
            << ',' << row.near_field.rmse << ',' << row.near_field.ssim << ',' << row.near_field.bias << ','
            << row.near_field.noise;
        for (double mae : row.still_mae) csv << ',' << mae;
        for (double mae : row.turn_mae) csv << ',' << mae;
        csv << ',' << row.still_noise << ',' << row.turn_noise << ',' << row.instability << "\n";
        rows.push_back(row);
        progress_bar("configurations", static_cast<int>(c + 1), static_cast<int>(configs.size()));
      }
    }
  }
  csv.close();

  // Aggregate each configuration over scenes and views: mean time, mean error against the
  // near-field reference (the one every estimator can be judged by).
  std::map<const aobench::Config*, std::pair<double, double>> totals;
  std::map<const aobench::Config*, double> own_totals, frame_totals, noise_totals, bias_totals, still_totals, turn_totals,
      instability_totals, still_noise_totals;
  std::map<const aobench::Config*, int> counts;
  for (const Row& row : rows) {
    totals[row.config].first += row.time_ms;
    totals[row.config].second += row.near_field.mae;
    own_totals[row.config] += row.own.mae;
    frame_totals[row.config] += row.frame_ms;
    noise_totals[row.config] += row.near_field.noise;
    bias_totals[row.config] += row.near_field.bias;
    still_totals[row.config] += row.still_mae[2];
    still_noise_totals[row.config] += row.still_noise;
    turn_totals[row.config] += row.turn_mae[2];
    instability_totals[row.config] += row.instability;
    ++counts[row.config];
  }
  std::vector<aobench::ChartPoint> points;
  std::vector<const aobench::Config*> order;
  for (const aobench::Config& config : configs) {
    const int n = std::max(counts[&config], 1);
    aobench::ChartPoint point{totals[&config].first / n, totals[&config].second / n, false,
                              config.name == "paper" || config.name == "default" ? config.name : ""};
    points.push_back(point);
    order.push_back(&config);
  }
  for (size_t i : aobench::pareto_front(points)) points[i].on_front = true;
  std::cout << "\nmean over " << options.scenes.size() * static_cast<size_t>(options.views)
            << " scene views (error: MAE against the near-field reference; own: against the estimator's own reference)\n";
  std::cout << std::left << std::setw(12) << "AO ms" << std::setw(12) << "frame ms" << std::setw(12) << "MAE" << std::setw(12)
            << "own MAE" << std::setw(12) << "bias" << std::setw(12) << "noise" << std::setw(12) << "MAE still16" << std::setw(12)
            << "noise st16" << std::setw(12) << "MAE turn16" << std::setw(12) << "instability"
            << "configuration\n";
  for (size_t i = 0; i < points.size(); ++i) {
    if (!points[i].on_front && points[i].mark.empty() && configs.size() > 40) continue;
    const int n = std::max(counts[order[i]], 1);
    std::cout << std::left << std::setw(12) << std::setprecision(4) << points[i].time_ms << std::setw(12)
              << frame_totals[order[i]] / n << std::setw(12) << points[i].error << std::setw(12) << own_totals[order[i]] / n
              << std::setw(12) << bias_totals[order[i]] / n << std::setw(12) << noise_totals[order[i]] / n << std::setw(12)
              << still_totals[order[i]] / n << std::setw(12) << still_noise_totals[order[i]] / n << std::setw(12)
              << turn_totals[order[i]] / n << std::setw(12) << instability_totals[order[i]] / n << order[i]->name
              << (points[i].on_front ? "  [front]" : "") << (points[i].mark.empty() ? "" : "  <- " + points[i].mark) << "\n";
  }
  if (!aobench::write_chart(options.chart, points, "aobench " + options.size, "MAE vs near-field reference", error)) {
    std::cerr << "error: " << error << "\n";
    return 1;
  }
  // The same configurations over time and the error's high-frequency noise, with that front.
  std::vector<aobench::ChartPoint> noise_points = points;
  for (size_t i = 0; i < noise_points.size(); ++i) {
    noise_points[i].error = noise_totals[order[i]] / std::max(counts[order[i]], 1);
    noise_points[i].on_front = false;
  }
  for (size_t i : aobench::pareto_front(noise_points)) noise_points[i].on_front = true;
  if (!aobench::write_chart(options.noise_chart, noise_points, "aobench " + options.size,
                            "high-frequency noise of the error (|e - 5x5 box(e)|)", error)) {
    std::cerr << "error: " << error << "\n";
    return 1;
  }
  std::cout << "wrote " << options.csv << ", " << options.chart << " and " << options.noise_chart << "\n";
  return 0;
}
