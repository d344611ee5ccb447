#include "app/render_command.h"

#include "scene/animation.h"

#include "base/image_codec.h"
#include "dump.h"
#include "gl/caps.h"
#include "gl/gl_api.h"
#include "gl/session.h"
#include "image_io.h"
#include "light_field_render.h"
#include "platform/platform.h"
#include "playback/timeline.h"
#include "scene/load.h"
#include "shader_cache.h"

#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <ostream>

namespace app {
namespace {

// Writes the raw and blurred AO, world-space position and normal, linear depth and the camera, so
// that the AO can be evaluated by anyone at exactly the surface points the SSAO pass saw.
bool write_dump(const std::string& dir, const render::Renderer& renderer, const scene::Camera& camera,
                const RenderOptions& options, const std::string& platform_description, std::string& error) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    error = dir + ": cannot create the dump folder (" + ec.message() + ")";
    return false;
  }
  const int w = options.frame.width, h = options.frame.height;
  const render::WorldSurface surface = render::read_world_surface(renderer.targets(), render::view_of(camera));
  const glm::dmat4 view = camera.view();
  const glm::dmat4 projection = camera.projection();
  const std::string base = dir + "/";
  if (!write_view_exrs(base, renderer.programs(), renderer.targets(), surface, error)) return false;

  const shared_layout::SsaoParams& params = renderer.ssao_params();
  nlohmann::json radii = nlohmann::json::array();
  for (int k = 0; k < params.radius_count; ++k) radii.push_back(params.radii[k].x);
  nlohmann::json kernel = nlohmann::json::array();
  for (int i = 0; i < params.samples; ++i) kernel.push_back({params.kernel[i].x, params.kernel[i].y, params.kernel[i].z});
  const render::FrameSettings& frame = options.frame;
  nlohmann::json doc = {
      {"scene", options.scene},
      {"platform", platform_description},
      {"width", w},
      {"height", h},
      {"image_rows", "EXR rows are top to bottom; pixel (x, y) has its centre at NDC ((x+0.5)/w*2-1, 1-(y+0.5)/h*2)"},
      {"camera",
       {{"eye", {camera.eye.x, camera.eye.y, camera.eye.z}},
        {"target", {camera.target.x, camera.target.y, camera.target.z}},
        {"up", {camera.up.x, camera.up.y, camera.up.z}},
        {"fov_y_deg", glm::degrees(camera.fov_y)},
        {"near", camera.near},
        {"far", camera.far},
        {"view", matrix_json(view)},
        {"projection", matrix_json(projection)},
        {"matrix_layout", "column-major: view[c] is column c"}}},
      {"ao",
       {{"enabled", frame.ao},
        {"estimator", std::string(ssao::name(frame.ao_settings.estimator))},
        {"precision", std::string(ssao::name(frame.ao_settings.precision))},
        {"resolution", frame.ao_settings.half_resolution ? "half" : "full"},
        {"depth_chain", frame.ao_settings.depth_chain},
        {"skip_radii", frame.ao_settings.skip_radii},
        {"samples", params.samples},
        {"radii", radii},
        {"bias_fraction", params.depth_bias},
        {"pattern", std::string(ssao::name(frame.ao_settings.pattern))},
        {"kernel_unit_ball", kernel},
        {"blur", std::string(ssao::name(frame.blur.mode))},
        {"blur_radius", frame.blur.radius},
        {"blur_sigma", frame.blur.sigma},
        {"temporal", frame.temporal},
        {"history", frame.history},
        {"frames_averaged", renderer.ao_frames_averaged()}}},
      {"files",
       {{"ao_raw.exr", "the last frame's own AO, before temporal accumulation and blur, [0,1], 0 on background"},
        {"ao_blurred.exr",
         "the AO the frame was shaded with: the average over ao.frames_averaged frames (samples "
         "turned anew each frame), then blurred when blur is on"},
        {"position.exr", "world-space position of the visible surface; A = 1 on objects, 0 on background"},
        {"normal.exr", "world-space unit normal; A as above"},
        {"depth.exr", "linear view depth (distance along the view axis), 0 on background"}}}};
  return write_json(base + "camera.json", doc, error);
}

}  // namespace

std::unique_ptr<gl::Session> open_render_session(const std::string& platform, int width, int height, std::ostream& err,
                                                 const std::string& shader_cache) {
  platform::Options options;
  options.name = platform;
  options.size = {width, height};
  const std::string shader_dir = shader_cache_dir(shader_cache);
  if (const std::string problem = prepare_driver_cache(shader_dir); !problem.empty())
    err << "note: Mesa's shader cache stays where it was: " << problem << "\n";
  std::string error;
  std::unique_ptr<gl::Session> session = gl::Session::open(options, error);
  if (!session) {
    err << "error: " << error << "\n";
    return session;
  }
  const std::string line = open_program_store(*session, shader_dir);
  if (!shader_dir.empty() && !session->programs().store()) err << "note: " << line << "\n";
  return session;
}

scene::LoadOptions load_options_for(const gl::Caps& caps) {
  scene::LoadOptions options;
  options.max_texture_size = std::min(options.max_texture_size, caps.max_texture_size);
  return options;
}

scene::Framing framing_of(const playback::Camera& camera) {
  scene::Framing framing;
  framing.azimuth_deg = camera.azimuth_deg;
  framing.elevation_deg = camera.elevation_deg;
  framing.distance = camera.distance;
  framing.fov_y_deg = camera.fov_deg;
  return framing;
}

scene::Camera camera_for(const playback::Camera& camera, const scene::Bounds& bounds,
                         const std::vector<scene::FileCamera>& cameras, int width, int height, std::string* note) {
  if (camera.file_index >= 0) {
    const size_t index = static_cast<size_t>(camera.file_index);
    if (index < cameras.size() && cameras[index].perspective && cameras[index].unplaced.empty())
      return scene::from_file(cameras[index], bounds, width, height);
    if (!note) return scene::frame(bounds, framing_of(camera), width, height);
    const std::string name = "camera " + std::to_string(camera.file_index);
    if (index >= cameras.size())
      *note = name + ": the scene has " + std::to_string(cameras.size()) + " camera" + (cameras.size() == 1 ? "" : "s") +
              "; framed by the player instead";
    else if (!cameras[index].perspective)
      *note = name + " is orthographic, which the player does not draw; framed instead";
    else
      *note = name + " (node " + std::to_string(cameras[index].node) + "): " + std::string(cameras[index].unplaced) +
              "; framed instead";
  }
  return scene::frame(bounds, framing_of(camera), width, height);
}

scene::Camera render_camera(const RenderOptions& options, const scene::Scene& scene, int width, int height, std::string* note) {
  // A one-item playback with a still camera: the same timeline says what `play` renders.
  playback::Playlist playlist = playback::playlist_from_scenes({options.scene}, 1.0, 1.0);
  playback::CameraPath& path = playlist.items.front().camera;
  path.motion = playback::Motion::still;
  path.azimuth_deg = options.framing.azimuth_deg;
  path.elevation_deg = options.framing.elevation_deg;
  path.distance = options.framing.distance;
  path.fov_deg = options.framing.fov_y_deg;
  if (options.file_camera >= 0) {
    path.motion = playback::Motion::file;
    path.index = options.file_camera;
  }
  playback::Timeline timeline(std::move(playlist), 0.0, 0.0);
  return camera_for(timeline.at(0.0, 0.0).camera, scene.bounds, scene.cameras, width, height, note);
}

int run_render(const RenderOptions& options, std::ostream& out, std::ostream& err) {
  if (!options.display.empty()) return run_render_light_field(options, out, err);
  if (!options.modules_dir.empty() || !options.native_output.empty() || options.view_probe) {
    err << "error: "
        << (!options.modules_dir.empty()     ? "--modules-dir"
            : !options.native_output.empty() ? "--native"
                                             : "--view-probe")
        << ": needs --display FILE (a light field display)\n";
    return 2;
  }
  const auto session =
      open_render_session(options.platform, options.frame.width, options.frame.height, err, options.shader_cache);
  if (!session) return 1;
  std::string error;
  const platform::Platform& platform = session->platform();
  const gl::Caps& caps = session->caps();

  // Loaded with the context's texture limit known, so a texture this GPU cannot hold is drawn white.
  const auto load_start = std::chrono::steady_clock::now();
  scene::Scene scene;
  if (!scene::load(options.scene, scene, error, err, load_options_for(caps)) ||
      !scene::load_environment_spec(options.environment, scene.environment, error)) {
    err << "error: " << error << "\n";
    return 1;
  }
  const double load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - load_start).count();
  int selection = scene::Rig::kAllAnimations;
  if (!scene::select_animation(scene.rig.get(), options.animation, selection, error)) {
    err << "error: --animation: " << error << "\n";
    return 2;
  }
  if (scene.rig) {
    scene::Pose pose(scene.rig);
    pose.at(selection, options.time);
    scene::pose_instances(scene, pose);
    scene::pose_meshes(scene, pose);
  }
  render::Renderer renderer;
  const render::PresentTarget target{platform.framebuffer(), 0, 0, platform.srgb_framebuffer()};
  if (!renderer.init(*session, target, error) || !renderer.upload(scene, error) || !renderer.configure(options.frame, error)) {
    err << "error: " << error << "\n";
    return 1;
  }
  std::string camera_note;
  const scene::Camera camera = render_camera(options, scene, options.frame.width, options.frame.height, &camera_note);
  if (!camera_note.empty()) err << "warning: " << camera_note << "\n";

  const int frames = std::max(1, options.frames);
  std::vector<render::PassTimes> times;
  int reused = 0;
  for (int frame = 0; frame < frames; ++frame) {
    renderer.render(camera);
    times.push_back(renderer.collect_times());
    reused += renderer.reused_ao() ? 1 : 0;
  }
  if (!renderer.gl_error().empty()) {
    err << "error: " << renderer.gl_error() << "\n";
    return 1;
  }
  if (!options.output.empty()) {
    if (!write_png(options.output, options.frame.width, options.frame.height, renderer.read_color(), error)) {
      err << "error: " << error << "\n";
      return 1;
    }
  }
  if (!options.dump_dir.empty() &&
      !write_dump(options.dump_dir, renderer, camera, options, std::string(platform.name()) + ": " + caps.renderer, error)) {
    err << "error: " << error << "\n";
    return 1;
  }

  // The first frame pays for shader compilation and first-touch allocation; with more than one
  // frame it is left out of the median.
  const size_t first = times.size() > 1 ? 1 : 0;
  out << scene.name << ": " << scene.triangle_count() << " triangles, " << options.frame.width << "x" << options.frame.height
      << ", " << platform.name() << " (" << caps.renderer << "), loaded in " << std::fixed << std::setprecision(1) << load_ms
      << " ms\n";
  out << (times.front().gpu_timed ? "GPU time per pass" : "time per pass (CPU clock around glFinish; no timer queries)")
      << ", median of " << times.size() - first << " frame(s):\n";
  double total = 0.0;
  for (int pass = 0; pass < render::kPassCount; ++pass) {
    std::vector<double> samples;
    for (size_t f = first; f < times.size(); ++f) samples.push_back(times[f].ms[static_cast<size_t>(pass)]);
    std::sort(samples.begin(), samples.end());
    const double median = samples[samples.size() / 2];
    if (median < 0.0) {
      out << "  " << std::left << std::setw(16) << render::pass_name(static_cast<render::Pass>(pass)) << "   skipped\n";
      continue;
    }
    total += median;
    out << "  " << std::left << std::setw(16) << render::pass_name(static_cast<render::Pass>(pass)) << std::right << std::setw(9)
        << std::setprecision(3) << median << " ms\n";
  }
  out << "  " << std::left << std::setw(16) << "total" << std::right << std::setw(9) << total << " ms\n";
  if (options.frame.prepass == render::Prepass::automatic) {
    if (renderer.raster_ms_without_prepass() >= 0.0)
      out << "depth prepass: auto kept it " << (renderer.prepass_in_use() ? "on" : "off") << " (prepass + g-buffer "
          << renderer.raster_ms_with_prepass() << " ms, g-buffer alone " << renderer.raster_ms_without_prepass() << " ms)\n";
    else
      out << "depth prepass: auto needs two frames to choose (--frames 3 or more)\n";
  }
  out << "shaders: " << program_counts(session->programs()) << "\n";
  if (renderer.ao_frames_averaged() > 1)
    out << "AO averaged over " << renderer.ao_frames_averaged()
        << " frames (temporal accumulation; --temporal off for one frame's)\n";
  if (reused > 0)
    out << "AO reused on " << reused << " of " << frames
        << " frames (camera still, history full; --reuse-ao off to time every frame)\n";
  if (!options.output.empty()) out << "wrote " << options.output << "\n";
  if (!options.dump_dir.empty()) out << "dumped AO, position, normal, depth and camera.json to " << options.dump_dir << "\n";
  return 0;
}

int run_info(const std::string& platform_name, const std::string& shader_cache, std::ostream& out, std::ostream& err) {
  const auto session = open_render_session(platform_name, 64, 64, err, shader_cache);
  if (!session) return 1;
  const platform::Platform& platform = session->platform();
  const gl::Caps& caps = session->caps();
  out << "platform:        " << platform.name() << " (" << platform.description() << ")\n";
  out << "GL renderer:     " << caps.renderer << "\n";
  out << "GL version:      " << caps.version << "\n";
  out << "GLSL version:    " << caps.shading_language << "\n";
  out << "compute:         " << caps.max_compute_work_group_invocations << " invocations per group, textures up to "
      << caps.max_texture_size << "\n";
  out << "extensions used:\n";
  for (const std::string& extension : platform.extensions_used()) out << "  " << extension << "  yes\n";
  for (const auto& [extension, present] : caps.extensions_used())
    out << "  " << extension << "  " << (present ? "yes" : "no") << "\n";
  out << "per-pass timing: " << (caps.timer_query ? "GPU timer queries" : "CPU clock around glFinish") << "\n";
  out << "image files:     " << base::images::describe() << "\n";
  if (const gl::ProgramStore* store = session->programs().store()) out << "program binaries: " << store->dir() << "\n";
  return 0;
}

}  // namespace app
