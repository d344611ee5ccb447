// lfbench: light field output measured. (1) How far the per-vertex world-to-image transform bends
// long edges: for every triangle edge of each scene and a spread of modules, the largest distance in
// pixels between where the rasteriser draws an edge point and where the module shows it. (2) The
// frame cost of 1, 8, 32 and 80 modules at 1024x768 (CPU clock around glFinish; llvmpipe has no
// timer queries), with and without AO, so that the SSAO cost per module can be read off. (3) A
// 45-view quilt. (4) View consistency: the spread of AO for one world point across the modules that
// see it, against the spread between neighbouring pixels of one module (its noise).
#include "gl/caps.h"
#include "gl/gl_api.h"
#include "gl/session.h"
#include "lightfield/display_file.h"
#include "platform/platform.h"
#include "render/light_field.h"
#include "render/readback.h"
#include "scene/load.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>

namespace {

struct Options {
  std::vector<std::string> scenes{"builtin:demo"};
  std::string board_dir = "board/displays";
  std::string platform = "auto";
  std::string size = "1024x768";
  std::vector<int> module_counts{1, 8, 32, 80};
  int frames = 3;
  bool edges_only = false;
};

bool load_scene(const std::string& spec, scene::Scene& scene) {
  std::string error;
  std::ostringstream log;
  if (scene::load(spec, scene, error, log)) return true;
  std::cerr << "lfbench: " << error << "\n";
  return false;
}

// Every edge once (as a pair of world positions), in world space.
std::vector<std::pair<glm::dvec3, glm::dvec3>> edges_of(const scene::Scene& scene) {
  std::vector<std::pair<glm::dvec3, glm::dvec3>> edges;
  for (const scene::Instance& instance : scene.instances) {
    const scene::Mesh& mesh = scene.meshes[static_cast<size_t>(instance.mesh)];
    std::set<std::pair<uint32_t, uint32_t>> seen;
    for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
      for (int e = 0; e < 3; ++e) {
        uint32_t a = mesh.indices[t + static_cast<size_t>(e)], b = mesh.indices[t + static_cast<size_t>((e + 1) % 3)];
        if (a > b) std::swap(a, b);
        if (!seen.insert({a, b}).second) continue;
        edges.emplace_back(glm::dvec3(instance.world * glm::dvec4(glm::dvec3(mesh.vertices[a].position), 1.0)),
                           glm::dvec3(instance.world * glm::dvec4(glm::dvec3(mesh.vertices[b].position), 1.0)));
      }
  }
  return edges;
}

void measure_edges(const Options& options) {
  std::cout << "# Edge bending: pixels between where the rasteriser draws an edge point and where the module shows it\n";
  std::cout << std::left << std::setw(22) << "scene" << std::setw(22) << "display" << std::right << std::setw(9) << "edges"
            << std::setw(11) << "max px" << std::setw(11) << "p99.9 px" << std::setw(14) << "edges >0.5px"
            << "\n";
  for (const std::string& spec : options.scenes) {
    scene::Scene scene;
    if (!load_scene(spec, scene)) continue;
    const auto edges = edges_of(scene);
    for (const char* file : {"desk-8.toml", "holovizio-c80.toml"}) {
      lightfield::Display display;
      std::string error;
      if (!lightfield::load_display(options.board_dir + "/" + file, display, error)) {
        std::cerr << "lfbench: " << error << "\n";
        continue;
      }
      const lightfield::ModulesDisplay& m = display.modules;
      const auto roi = lightfield::roi_transform(lightfield::world_roi(m, {scene.bounds.min, scene.bounds.max}), m.physical_roi);
      if (!roi) continue;
      const int count = static_cast<int>(m.module_x.size());
      std::vector<double> worst_per_edge(edges.size(), 0.0);
      for (int k : {0, count / 4, count / 2, 3 * count / 4, count - 1}) {
        const lightfield::Module module = lightfield::module_of(m, k);
        for (size_t e = 0; e < edges.size(); ++e)
          worst_per_edge[e] = std::max(worst_per_edge[e], lightfield::edge_error_pixels(module, roi->to_physical(edges[e].first),
                                                                                        roi->to_physical(edges[e].second)));
      }
      std::vector<double> sorted = worst_per_edge;
      std::sort(sorted.begin(), sorted.end());
      const size_t over = static_cast<size_t>(std::count_if(sorted.begin(), sorted.end(), [](double v) { return v > 0.5; }));
      std::cout << std::left << std::setw(22) << scene.name.substr(0, 21) << std::setw(22) << file << std::right << std::setw(9)
                << edges.size() << std::fixed << std::setprecision(3) << std::setw(11) << (sorted.empty() ? 0.0 : sorted.back())
                << std::setw(11) << (sorted.empty() ? 0.0 : sorted[sorted.size() * 999 / 1000]) << std::setw(14) << over << "\n";
    }
  }
  std::cout << "\n";
}

double median_frame_ms(render::LightFieldRenderer& renderer, int frames) {
  renderer.render();
  gl::api.Finish();  // warm-up: shader variants and first-touch allocation
  std::vector<double> ms;
  for (int f = 0; f < frames; ++f) {
    const auto start = std::chrono::steady_clock::now();
    renderer.render();
    gl::api.Finish();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  std::sort(ms.begin(), ms.end());
  return ms[ms.size() / 2];
}

bool time_display(gl::Session& session, const scene::Scene& scene, const lightfield::Display& display, double& with_ao,
                  double& without_ao, int& rendered, int frames) {
  render::LightFieldRenderer renderer;
  render::FrameSettings settings;
  settings.reuse_static_ao = false;
  std::string error;
  const scene::Camera camera = scene::frame(scene.bounds, {}, display.quilt.view_width, display.quilt.view_height);
  if (!renderer.init(session, error) || !renderer.upload(scene, error) || !renderer.configure(display, settings, camera, error)) {
    std::cerr << "lfbench: " << error << "\n";
    return false;
  }
  with_ao = median_frame_ms(renderer, frames);
  rendered = renderer.output().rendered_views();
  settings.ao = false;
  if (!renderer.configure(display, settings, camera, error)) {
    std::cerr << "lfbench: " << error << "\n";
    return false;
  }
  without_ao = median_frame_ms(renderer, frames);
  return true;
}

struct ModuleCapture {
  render::WorldSurface surface;
  std::vector<float> raw, shaded;  // AO before the blur and as shaded, full resolution, rows bottom-up
};

// Mean over points of the standard deviation of a set of AO values. Points whose AO is near zero are
// left out: an open face is unoccluded whatever the sample turns, and would dilute the noise.
struct Spread {
  double sum = 0.0;
  long count = 0;
  void add(const std::vector<float>& values) {
    if (values.size() < 2) return;
    double mean = 0.0, square = 0.0;
    for (float v : values) mean += v;
    mean /= static_cast<double>(values.size());
    if (mean < 0.05) return;
    for (float v : values) square += (v - mean) * (v - mean);
    sum += std::sqrt(square / static_cast<double>(values.size() - 1));
    ++count;
  }
  double value() const { return count > 0 ? sum / count : 0.0; }
};

void measure_consistency(gl::Session& session, const scene::Scene& scene, const lightfield::Display& display, bool pixel_turns,
                         ssao::Blur blur) {
  render::LightFieldRenderer renderer;
  render::FrameSettings settings;
  settings.ao_settings.estimator = ssao::Estimator::hemisphere;
  settings.ao_settings.half_resolution = false;
  settings.blur.mode = blur;
  std::string error;
  if (!renderer.init(session, error) || !renderer.upload(scene, error) || !renderer.configure(display, settings, {}, error)) {
    std::cerr << "lfbench: " << error << "\n";
    return;
  }
  renderer.output().set_pixel_turns(pixel_turns);
  std::vector<ModuleCapture> captures(static_cast<size_t>(renderer.output().views()));
  renderer.output().set_after_view([&](int k, const render::View&, const render::ViewTargets& targets) {
    ModuleCapture& c = captures[static_cast<size_t>(k)];
    c.surface = render::read_module_surface(targets);
    for (const glm::vec2& ao : render::read_ao(targets.ao_raw, targets.ao_width(), targets.ao_height())) c.raw.push_back(ao.x);
    for (const glm::vec2& ao : render::read_ao_full(renderer.programs(), targets)) c.shaded.push_back(ao.x);
  });
  renderer.render();
  const int w = display.modules.width, h = display.modules.height;
  const double pixel_world =
      (display.modules.footprint.y - display.modules.footprint.x) / w / renderer.output().view(0).module->roi.scale;
  Spread across_raw, across_shaded, within_raw, within_shaded;  // raw: before the blur; shaded: after
  for (int k = 0; k < renderer.output().views(); ++k) {
    const ModuleCapture& c = captures[static_cast<size_t>(k)];
    if (c.surface.position.empty()) continue;
    for (int y = 1; y + 1 < h; y += 2)
      for (int x = 1; x + 1 < w; x += 2) {
        const size_t i = static_cast<size_t>(y * w + x);
        if (c.surface.position[i * 4 + 3] <= 0.0f) continue;
        // Within the module: the 3x3 neighbourhood, where it is all surface.
        std::vector<float> near_raw, near_shaded;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const size_t j = static_cast<size_t>((y + dy) * w + x + dx);
            if (c.surface.position[j * 4 + 3] <= 0.0f) continue;
            near_raw.push_back(c.raw[j]);
            near_shaded.push_back(c.shaded[j]);
          }
        if (near_raw.size() == 9) {
          within_raw.add(near_raw);
          within_shaded.add(near_shaded);
        }
        // Across modules: the pixel of each other module that shows this point, where it is this point.
        const glm::dvec3 world(c.surface.position[i * 4], c.surface.position[i * 4 + 1], c.surface.position[i * 4 + 2]);
        std::vector<float> same_raw{c.raw[i]}, same_shaded{c.shaded[i]};
        for (int j = 0; j < renderer.output().views(); ++j) {
          if (j == k || captures[static_cast<size_t>(j)].surface.position.empty()) continue;
          const render::ModuleView& mv = *renderer.output().view(j).module;
          const auto image = lightfield::physical_to_image(mv.module, mv.roi.to_physical(world));
          if (!image || image->x < 0 || image->y < 0 || image->x >= w || image->y >= h) continue;
          const int u = static_cast<int>(image->x), v_bottom = h - 1 - static_cast<int>(image->y);
          const size_t p = static_cast<size_t>(v_bottom * w + u);
          const ModuleCapture& other = captures[static_cast<size_t>(j)];
          const glm::dvec3 seen(other.surface.position[p * 4], other.surface.position[p * 4 + 1],
                                other.surface.position[p * 4 + 2]);
          if (other.surface.position[p * 4 + 3] <= 0.0f || glm::length(seen - world) > pixel_world) continue;  // hidden there
          same_raw.push_back(other.raw[p]);
          same_shaded.push_back(other.shaded[p]);
        }
        across_raw.add(same_raw);
        across_shaded.add(same_shaded);
      }
  }
  std::cout << std::fixed << std::setprecision(4) << std::left << std::setw(26)
            << (pixel_turns ? "  turns by pixel tile" : "  turns by world cell") << std::setw(10) << ssao::name(blur)
            << std::right << std::setw(12) << across_raw.value() << std::setw(12) << across_shaded.value() << std::setw(12)
            << within_raw.value() << std::setw(12) << within_shaded.value() << std::setw(9) << across_raw.count << "\n";
}

int run(const Options& options) {
  measure_edges(options);
  if (options.edges_only) return 0;
  int width = 0, height = 0;
  char x = 0;
  std::istringstream size(options.size);
  if (!(size >> width >> x >> height) || x != 'x' || width < 1 || height < 1) {
    std::cerr << "lfbench: --size: expected WxH, got '" << options.size << "'\n";
    return 2;
  }
  platform::Options platform_options;
  platform_options.name = options.platform;
  platform_options.size = {64, 64};
  std::string error;
  const auto session = gl::Session::open(platform_options, error);
  if (!session) {
    std::cerr << "lfbench: " << error << "\n";
    return 1;
  }
  const gl::Caps& caps = session->caps();
  std::cout << "# Frame cost on " << session->platform().name() << " (" << caps.renderer
            << "), CPU clock around glFinish, median of " << options.frames << " frames after one warm-up\n";
  lightfield::Display c80;
  if (!lightfield::load_display(options.board_dir + "/holovizio-c80.toml", c80, error)) {
    std::cerr << "lfbench: " << error << "\n";
    return 1;
  }
  for (const std::string& spec : options.scenes) {
    scene::Scene scene;
    if (!load_scene(spec, scene)) return 1;
    std::cout << scene.name << ", modules of " << width << "x" << height << " on the HoloVizio C80 geometry:\n";
    std::cout << std::right << std::setw(8) << "modules" << std::setw(10) << "rendered" << std::setw(12) << "frame ms"
              << std::setw(12) << "no-AO ms" << std::setw(10) << "x one" << std::setw(16) << "SSAO ms/module"
              << "\n";
    double one = 0.0;
    for (int count : options.module_counts) {
      lightfield::Display display = c80;
      display.modules.width = width;
      display.modules.height = height;
      display.modules.module_x.clear();
      for (int k = 0; k < count; ++k) display.modules.module_x.push_back(count == 1 ? 0.0 : -1.0 + 2.0 * k / (count - 1));
      double with_ao = 0.0, without_ao = 0.0;
      int rendered = 0;
      if (!time_display(*session, scene, display, with_ao, without_ao, rendered, options.frames)) return 1;
      if (count == options.module_counts.front()) one = with_ao / count;
      std::cout << std::fixed << std::setprecision(2) << std::setw(8) << count << std::setw(10) << rendered << std::setw(12)
                << with_ao << std::setw(12) << without_ao << std::setw(10) << with_ao / one << std::setw(16)
                << (with_ao - without_ao) / std::max(1, rendered) << "\n";
    }
    lightfield::Display quilt;
    if (!lightfield::load_display(options.board_dir + "/looking-glass-portrait.toml", quilt, error)) {
      std::cerr << "lfbench: " << error << "\n";
      return 1;
    }
    double with_ao = 0.0, without_ao = 0.0;
    int rendered = 0;
    if (!time_display(*session, scene, quilt, with_ao, without_ao, rendered, options.frames)) return 1;
    lightfield::Display desk;
    if (!lightfield::load_display(options.board_dir + "/desk-8.toml", desk, error)) {
      std::cerr << "lfbench: " << error << "\n";
      return 1;
    }
    std::cout << scene.name << " on desk-8.toml (" << desk.views() << " modules of " << desk.modules.width << "x"
              << desk.modules.height
              << ", hemisphere): standard deviation of AO for one world point across the modules that see it\n"
              << "(across) and across a 3x3 pixel neighbourhood of one module (within), before the blur (raw) and after, where "
                 "AO >= 0.05\n";
    std::cout << std::left << std::setw(26) << "  sample turns" << std::setw(10) << "blur" << std::right << std::setw(12)
              << "across raw" << std::setw(12) << "across" << std::setw(12) << "within raw" << std::setw(12) << "within"
              << std::setw(9) << "points"
              << "\n";
    for (const bool pixel_turns : {false, true})
      for (const ssao::Blur blur : {ssao::Blur::off, ssao::Blur::bilateral})
        measure_consistency(*session, scene, desk, pixel_turns, blur);
    std::cout << "quilt " << quilt.quilt.columns << "x" << quilt.quilt.rows << " (" << rendered << " views of "
              << quilt.quilt.view_width << "x" << quilt.quilt.view_height << ") + interleave to "
              << quilt.quilt.calibration.screen_width << "x" << quilt.quilt.calibration.screen_height << ": " << with_ao
              << " ms a frame (" << without_ao << " without AO; " << (with_ao - without_ao) / std::max(1, rendered)
              << " ms SSAO per view)\n\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  CLI::App cli{"lfbench: light field output measured (edge bending, frame cost per module count, quilt)"};
  cli.add_option("scenes", options.scenes, "Scenes (.gltf, .glb, builtin:NAME)")->capture_default_str();
  cli.add_option("--displays", options.board_dir, "Folder with holovizio-c80.toml, desk-8.toml and looking-glass-portrait.toml")
      ->capture_default_str();
  cli.add_option("--platform", options.platform, "GL platform: " + platform::names_text())->capture_default_str();
  cli.add_option("--size", options.size, "Each module's image size for the timing")->capture_default_str();
  cli.add_option("--modules", options.module_counts, "Module counts to time")->capture_default_str();
  cli.add_option("--frames", options.frames, "Frames per measurement (after one warm-up)")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cli.add_flag("--edges-only", options.edges_only, "Only the edge-bending measurement (no GL)");
  CLI11_PARSE(cli, argc, argv);
  return run(options);
}
