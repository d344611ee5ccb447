// ao4d: ray-traced ambient occlusion of 4D objects given as tetrahedral boundary meshes.
#include "ao4d/render.hpp"
#include "ao4d/scene.hpp"
#include "ao4d/shapes.hpp"

#include <CLI/CLI.hpp>

#include <unistd.h>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>

namespace {

// A one-line bar redrawn in place; only on a terminal, so logs and pipes stay clean.
ao4d::ProgressFn progress_bar(const std::string& label, bool enabled) {
  if (!enabled || !isatty(STDERR_FILENO)) return {};
  return [label](std::size_t done, std::size_t total) {
    constexpr int kWidth = 40;
    const double f = total ? static_cast<double>(done) / static_cast<double>(total) : 1.0;
    const int filled = static_cast<int>(f * kWidth);
    std::fprintf(stderr, "\r%-14s [%s%s] %3d%%", label.c_str(), std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(kWidth - filled), '.').c_str(), static_cast<int>(f * 100));
    if (done >= total) std::fputc('\n', stderr);
    std::fflush(stderr);
  };
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "Ray-traced ambient occlusion of 4D objects whose boundary is a tetrahedral mesh in R^4.\n"
      "Renders a 3D image volume (camera looking along +w) and writes OUT.vti, OUT.ao.nrrd,\n"
      "OUT.depth.nrrd, OUT.png and OUT.tet4 (the mesh with per-vertex AO); or, with --points,\n"
      "prints the AO of each given point on its own line.",
      "ao4d"};
  std::string shape, mesh_file, points_file, out;
  int size = 50, rays = 128, grid = 10;
  unsigned threads = 0;
  double radius = 0;
  std::uint64_t seed = 1;
  bool cosine = false, perspective = false, quiet = false;
  auto* shape_opt = app.add_option("--shape", shape, "built-in shape: " + ao4d::shape_list());
  auto* mesh_opt = app.add_option("--mesh", mesh_file, "mesh file: 'v x y z w' and 't a b c d' lines (1-based), see README.md");
  shape_opt->excludes(mesh_opt);
  mesh_opt->excludes(shape_opt);
  app.add_option("--points", points_file,
                 "evaluate AO at the points of FILE ('px py pz pw nx ny nz nw' per line) and print one value per line");
  app.add_option("-o,--output", out, "output path prefix for the volume and mesh files (required without --points)");
  app.add_option("--size", size, "voxels per axis of the image volume")->default_val(size)->check(CLI::Range(1, 1024));
  app.add_option("--rays", rays, "AO rays per point")->default_val(rays)->check(CLI::Range(1, 1 << 20));
  app.add_option("--radius", radius, "AO ray length; default: a quarter of the scene's bounding-box diagonal")
      ->check(CLI::PositiveNumber);
  app.add_option("--seed", seed, "random seed; results do not depend on --threads")->default_val(seed);
  app.add_flag("--cosine", cosine, "cosine-weighted directions instead of uniform ones over the hemisphere");
  app.add_flag("--perspective", perspective, "perspective camera instead of orthographic projection along w");
  app.add_option("--grid", grid, "marching cells per axis for --shape")->default_val(grid)->check(CLI::Range(2, 200));
  app.add_option("--threads", threads, "worker threads; 0 uses every hardware thread")->default_val(threads);
  app.add_flag("-q,--quiet", quiet, "no progress bar");
  CLI11_PARSE(app, argc, argv);

  try {
    if (shape.empty() && mesh_file.empty()) throw CLI::RequiredError("--shape or --mesh");
    if (points_file.empty() && out.empty()) throw CLI::RequiredError("-o (or --points)");
  } catch (const CLI::Error& e) {
    return app.exit(e);
  }

  try {
    ao4d::TetMesh mesh = shape.empty() ? ao4d::read_mesh(mesh_file) : ao4d::make_shape(shape, grid);
    const std::string source = shape.empty() ? mesh_file : "shape " + shape;
    if (!quiet) std::fprintf(stderr, "%s: %zu vertices, %zu cells\n", source.c_str(), mesh.vertices.size(), mesh.cells.size());
    const ao4d::Scene scene(std::move(mesh));
    ao4d::AoParams params;
    params.radius = radius > 0 ? radius : 0.25 * scene.diagonal();
    params.rays = rays;
    params.seed = seed;
    params.cosine = cosine;
    params.threads = threads;

    if (!points_file.empty()) {
      const auto points = ao4d::read_points(points_file);
      const auto ao = ao4d::ambient_occlusion(scene, points, params, progress_bar("points", !quiet));
      for (double v : ao) std::printf("%.6f\n", v);
      if (out.empty()) return 0;
    }

    const std::filesystem::path prefix(out);
    if (prefix.has_parent_path()) std::filesystem::create_directories(prefix.parent_path());
    ao4d::CameraParams camera;
    camera.size = size;
    camera.projection = perspective ? ao4d::Projection::perspective : ao4d::Projection::orthographic;
    const ao4d::Volume volume = ao4d::render_volume(scene, camera, params, progress_bar("volume", !quiet));
    const auto with = [&](const char* suffix) { return std::filesystem::path(out + suffix); };
    ao4d::write_vti(with(".vti"), volume);
    ao4d::write_nrrd(with(".ao.nrrd"), volume, volume.ao);
    ao4d::write_nrrd(with(".depth.nrrd"), volume, volume.depth);
    ao4d::write_montage(with(".png"), volume);
    const auto vertex_ao = ao4d::vertex_ambient_occlusion(scene, params, progress_bar("vertices", !quiet));
    ao4d::write_mesh(with(".tet4"), scene.mesh(), &vertex_ao);
    if (!quiet) std::fprintf(stderr, "wrote %s.{vti,ao.nrrd,depth.nrrd,png,tet4}\n", out.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ao4d: error: %s\n", e.what());
    return 1;
  }
}
