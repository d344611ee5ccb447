// aoref: converged, ray-traced AO for the surface points of a `player render --dump`, and its error
// metrics against the player's SSAO. See README.md.
#include "aoref/dump.h"
#include "aoref/metrics.h"
#include "aoref/ray_scene.h"
#include "aoref/reference.h"
#include "scene/load.h"

#include <unistd.h>
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace {

int die(const std::string& message) {
  std::cerr << "error: " << message << "\n";
  return 1;
}

// A bar redrawn in place on a terminal; otherwise a line at each tenth, so logs stay short.
std::function<void(int, int)> progress_reporter(bool quiet) {
  if (quiet) return {};
  const bool terminal = isatty(STDERR_FILENO) != 0;
  auto last_tenth = std::make_shared<int>(-1);
  return [terminal, last_tenth](int done, int total) {
    const double fraction = total > 0 ? static_cast<double>(done) / total : 1.0;
    if (terminal) {
      constexpr int width = 40;
      const int filled = static_cast<int>(fraction * width);
      std::fprintf(stderr, "\r[%s%s] %3d%% (%d/%d rows)", std::string(static_cast<size_t>(filled), '#').c_str(),
                   std::string(static_cast<size_t>(width - filled), '.').c_str(), static_cast<int>(fraction * 100.0), done,
                   total);
      if (done == total) std::fputc('\n', stderr);
    } else {
      const int tenth = static_cast<int>(fraction * 10.0);
      if (tenth > *last_tenth) {
        *last_tenth = tenth;
        std::fprintf(stderr, "aoref: %d%% (%d/%d rows)\n", tenth * 10, done, total);
      }
    }
  };
}

}  // namespace

int main(int argc, char** argv) try {
  CLI::App app{
      "Ray-traced reference AO (Embree) at exactly the surface points of a `player render --dump DIR`.\n"
      "Writes OUT.exr: channel Y = reference AO, channel SE = its per-pixel binomial standard error,\n"
      "both 0 on background, same size and row order as the dump's EXRs."};
  std::string dump_dir, scene_spec, reference_name = "sphere", output, compare_path;
  aoref::ReferenceSettings settings;
  bool quiet = false;
  app.add_option("--dump", dump_dir, "Folder written by `player render --dump`")->required();
  app.add_option("--scene", scene_spec, "Scene to trace (builtin:NAME or a .gltf/.glb); default: \"scene\" of camera.json");
  app.add_option("--reference", reference_name,
                 "near-field: cosine-weighted hemisphere rays hitting within R; "
                 "sphere: hidden fraction of the shell [0.8R, R] for each radius of camera.json, merged by max "
                 "(what the player's estimator approximates)")
      ->check(CLI::IsMember({"near-field", "sphere"}))
      ->capture_default_str();
  app.add_option("--rays", settings.rays, "Rays per pixel (sphere: per pixel and radius)")
      ->check(CLI::Range(1, 1 << 20))
      ->capture_default_str();
  app.add_option("--radius", settings.radius, "near-field only: R in world units; default the largest radius of camera.json")
      ->check(CLI::PositiveNumber);
  app.add_option("--seed", settings.seed, "Seed of the per-pixel sample shifts (results are reproducible)")
      ->capture_default_str();
  app.add_option("--threads", settings.threads, "Worker threads; 0: one per hardware thread")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("-o,--output", output, "Output EXR (channels Y and SE)")->required();
  app.add_option("--compare", compare_path,
                 "An AO EXR of the dump's size (e.g. DIR/ao_blurred.exr): print MAE, RMSE, bias, SSIM and the MAE "
                 "within 3 px of depth edges over object pixels");
  std::string error_map_path;
  float error_scale = 0.1f;
  app.add_option("--error-map", error_map_path,
                 "With --compare: a PNG of estimate - reference per object pixel (red: estimate darker, blue: lighter, "
                 "full colour at --error-scale, white: no error)");
  app.add_option("--error-scale", error_scale, "The error that --error-map shows in full colour")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_flag("-q,--quiet", quiet, "No progress on stderr");
  CLI11_PARSE(app, argc, argv);

  settings.reference = *aoref::parse_reference(reference_name);
  if (settings.radius > 0.0 && settings.reference != aoref::Reference::near_field)
    return die("--radius: applies to --reference near-field only; the sphere reference uses the radii of camera.json");

  if (!error_map_path.empty() && compare_path.empty()) return die("--error-map: needs --compare (the estimate to map)");
  aoref::Dump dump;
  std::string error;
  if (!aoref::read_dump(dump_dir, dump, error)) return die(error);
  aoref::Image estimate;
  if (!compare_path.empty()) {
    if (!aoref::read_image(compare_path, estimate, error)) return die(error);
    if (!estimate.same_size(dump.depth))
      return die(compare_path + ": expected " + std::to_string(dump.depth.width) + "x" + std::to_string(dump.depth.height) +
                 " like the dump, found " + std::to_string(estimate.width) + "x" + std::to_string(estimate.height));
  }

  if (scene_spec.empty()) scene_spec = dump.scene;
  scene::Scene source;
  std::ostringstream log;
  if (!scene::load(scene_spec, source, error, log))
    return die(error +
               (scene_spec == dump.scene ? " (the scene named in " + dump_dir + "/camera.json; --scene overrides it)" : ""));
  if (!log.str().empty() && !quiet) std::cerr << log.str();
  aoref::RayScene rays;
  if (!rays.build(source, error)) return die(scene_spec + ": " + error);

  settings.progress = progress_reporter(quiet);
  const auto start = std::chrono::steady_clock::now();
  aoref::ReferenceResult result;
  if (!aoref::compute_reference(rays, dump.view, settings, result, error)) return die(error);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  aoref::Image out(result.ao.width, result.ao.height, 2);
  for (size_t i = 0; i < out.pixel_count(); ++i) {
    out.at(i, 0) = result.ao.at(i);
    out.at(i, 1) = result.standard_error.at(i);
  }
  if (!aoref::write_exr(output, out, {"Y", "SE"}, error)) return die(error);

  std::printf("%s: %zu triangles (%zu degenerate skipped), %dx%d, %zu object pixels\n", scene_spec.c_str(), rays.triangle_count(),
              rays.skipped_triangles(), out.width, out.height, result.object_pixels);
  std::printf(
      "reference %s: %d rays per pixel%s, %.3g rays in %.2f s (%.3g rays/s)\n",
      std::string(aoref::name(settings.reference)).c_str(), settings.rays,
      settings.reference == aoref::Reference::sphere ? (" per radius x " + std::to_string(dump.view.radii.size())).c_str() : "",
      static_cast<double>(result.rays_traced), seconds, seconds > 0.0 ? static_cast<double>(result.rays_traced) / seconds : 0.0);
  double ao_sum = 0.0;
  for (size_t i = 0; i < result.ao.pixel_count(); ++i) ao_sum += result.ao.at(i);
  std::printf("mean AO over object pixels %.4f\n",
              result.object_pixels ? ao_sum / static_cast<double>(result.object_pixels) : 0.0);
  std::printf("noise: binomial standard error per pixel max %.4f, mean %.4f\n", result.max_standard_error,
              result.mean_standard_error);
  std::printf("wrote %s (Y: AO, SE: standard error)\n", output.c_str());
  if (!compare_path.empty()) {
    const aoref::Metrics m = aoref::compare(estimate, result.ao, dump.depth);
    std::printf(
        "%s vs reference over %zu object pixels: MAE %.4f  RMSE %.4f  bias %+.4f  noise %.4f  SSIM %.4f  edge MAE %.4f (%zu px "
        "within 3 px of depth edges)\n",
        compare_path.c_str(), m.pixels, m.mae, m.rmse, m.bias, m.noise, m.ssim, m.edge_mae, m.edge_pixels);
    if (!error_map_path.empty()) {
      if (!aoref::write_rgb8(error_map_path, estimate.width, estimate.height,
                             aoref::error_map(estimate, result.ao, dump.depth, error_scale), error))
        return die(error);
      std::printf("wrote %s (estimate - reference, +-%g in full colour)\n", error_map_path.c_str(),
                  static_cast<double>(error_scale));
    }
  }
  return 0;
} catch (const std::exception& e) {
  return die(e.what());
}
