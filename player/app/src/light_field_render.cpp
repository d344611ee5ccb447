#include "light_field_render.h"

#include "app/render_command.h"
#include "dump.h"
#include "gl/caps.h"
#include "gl/gl_api.h"
#include "gl/session.h"
#include "image_io.h"
#include "platform/platform.h"
#include "render/light_field.h"
#include "render/readback.h"
#include "scene/load.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <ostream>

namespace app {
namespace {

bool make_folder(const std::string& dir, std::string& error) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) error = dir + ": cannot create the folder (" + ec.message() + ")";
  return !ec;
}

nlohmann::json vec3_json(const glm::dvec3& v) {
  return {v.x, v.y, v.z};
}

// DIR/module-K/ (modules) or DIR/view-K/ (quilt views): the AO before and after the blur, the world
// position and normal and the depth of the visible surface, and what the view was.
bool dump_view(const std::string& dir, int k, const render::View& view, const render::LightFieldRenderer& renderer,
               std::string& error) {
  const render::ViewTargets& targets = renderer.output().targets();
  const std::string base = dir + "/" + (view.module ? "module-" : "view-") + std::to_string(k);
  if (!make_folder(base, error)) return false;
  const int w = targets.settings().width, h = targets.settings().height;
  const render::WorldSurface surface =
      view.module ? render::read_module_surface(targets) : render::read_world_surface(targets, view);
  if (!write_view_exrs(base + "/", renderer.programs(), targets, surface, error)) return false;
  nlohmann::json doc = {{"index", k}, {"width", w}, {"height", h}};
  if (view.module) {
    const lightfield::Module& m = view.module->module;
    doc["module"] = {{"x", m.x},
                     {"z", m.z},
                     {"observer_distance", m.observer_distance},
                     {"observer_height", m.observer_height},
                     {"screen_height", m.screen_height},
                     {"footprint", {m.footprint0, m.footprint1}},
                     {"z_front", m.z_front},
                     {"z_back", m.z_back}};
    doc["world_to_physical"] = {{"scale", view.module->roi.scale}, {"offset", vec3_json(view.module->roi.offset)}};
    doc["files"] = {{"position.exr", "world position from the positions texture (Algorithm 2's input); A = 1 on objects"},
                    {"depth.exr", "distance from the observer line in physical units (D - z), 0 on background"},
                    {"normal.exr", "world-space unit normal; A as above"},
                    {"ao_raw.exr", "AO before blur"},
                    {"ao_blurred.exr", "AO after blur, as shaded"}};
  } else {
    doc["eye"] = vec3_json(view.eye);
    doc["view"] = matrix_json(view.view);
    doc["projection"] = matrix_json(view.projection);
    doc["files"] = {{"position.exr", "world position; A = 1 on objects"},
                    {"depth.exr", "linear view depth, 0 on background"},
                    {"normal.exr", "world-space unit normal"},
                    {"ao_raw.exr", "AO before blur"},
                    {"ao_blurred.exr", "AO after blur, as shaded"}};
  }
  doc["image_rows"] = "EXR rows are top to bottom";
  return write_json(base + "/view.json", doc, error);
}

}  // namespace

int run_render_light_field(const RenderOptions& options, std::ostream& out, std::ostream& err) {
  std::string error;
  lightfield::Display display;
  if (!lightfield::load_display(options.display, display, error)) {
    err << "error: " << error << "\n";
    return 1;
  }
  const bool quilt = display.type == lightfield::DisplayType::quilt;
  if (!options.native_output.empty() && !quilt) {
    err << "error: --native: " << options.display
        << " describes optical modules; only a quilt display has a native panel image\n";
    return 2;
  }
  if (options.view_probe && display.views() > 256) {
    err << "error: --view-probe: " << options.display << " has " << display.views()
        << " views; the probe draws view k as the 8-bit grey k, so at most 256\n";
    return 2;
  }
  // The default falls back to what modules can run (the output says so); asking for horizon by name
  // is a mistake to report.
  if (!quilt && options.frame.ao_settings.estimator == ssao::Estimator::horizon && options.estimator_given) {
    err << "error: --estimator: horizon searches screen-space slices and has no light field form; " << options.display
        << " describes optical modules, which take sphere or hemisphere\n";
    return 2;
  }

  // 64x64: every view renders into a framebuffer of its own.
  const auto session = open_render_session(options.platform, 64, 64, err, options.shader_cache);
  if (!session) return 1;
  const gl::Caps& caps = session->caps();
  scene::Scene scene;
  if (!scene::load(options.scene, scene, error, err, load_options_for(caps)) ||
      !scene::load_environment_spec(options.environment, scene.environment, error)) {
    err << "error: " << error << "\n";
    return 1;
  }
  render::LightFieldRenderer renderer;
  std::string camera_note;
  const scene::Camera camera = render_camera(options, scene, display.quilt.view_width, display.quilt.view_height, &camera_note);
  if (!camera_note.empty()) err << "warning: " << camera_note << "\n";
  if (!renderer.init(*session, error) || !renderer.upload(scene, error) ||
      !renderer.configure(display, options.frame, camera, error)) {
    err << "error: " << error << "\n";
    return 1;
  }
  render::LightFieldOutput& output = renderer.output();
  if (!output.adjustment().empty()) out << output.adjustment() << "\n";
  output.set_probe(options.view_probe);

  const int frames = std::max(1, options.frames);
  std::vector<double> frame_ms;
  std::string dump_error;
  for (int frame = 0; frame < frames; ++frame) {
    const bool last = frame + 1 == frames;
    const auto start = std::chrono::steady_clock::now();
    const bool dumping = last && !options.dump_dir.empty() && !options.view_probe;
    if (dumping)
      output.set_after_view([&](int k, const render::View& view, const render::ViewTargets&) {
        if (dump_error.empty()) dump_view(options.dump_dir, k, view, renderer, dump_error);
      });
    renderer.render();
    gl::api.Finish();
    if (!dumping) frame_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
  }
  if (!renderer.gl_error().empty()) {
    err << "error: " << renderer.gl_error() << "\n";
    return 1;
  }
  if (!dump_error.empty()) {
    err << "error: " << dump_error << "\n";
    return 1;
  }
  const glm::ivec2 output_size = output.output_size(), view_size = output.view_size();
  if (!write_png(options.output, output_size.x, output_size.y, output.read_output(), error)) {
    err << "error: " << error << "\n";
    return 1;
  }
  if (!options.modules_dir.empty()) {
    if (!make_folder(options.modules_dir, error)) {
      err << "error: " << error << "\n";
      return 1;
    }
    for (int k = 0; k < output.views(); ++k) {
      const std::string path = options.modules_dir + "/" + (quilt ? "view-" : "module-") + std::to_string(k) + ".png";
      if (!write_png(path, view_size.x, view_size.y, output.read_view(k), error)) {
        err << "error: " << error << "\n";
        return 1;
      }
    }
  }
  if (!options.native_output.empty()) {
    const glm::ivec2 native = output.native_size();
    if (!write_png(options.native_output, native.x, native.y, output.read_native(), error)) {
      err << "error: " << error << "\n";
      return 1;
    }
  }

  const std::string what = quilt ? "views" : "modules";
  out << scene.name << ": " << scene.triangle_count() << " triangles, " << options.display << ": " << output.views() << " "
      << what << " of " << view_size.x << "x" << view_size.y << ", " << session->platform().name() << " (" << caps.renderer
      << ")\n";
  const render::SubdivisionReport& split = renderer.subdivision();
  if (split.triangles_after > split.triangles_before || split.capped)
    out << "long edges split for the modules' transform: " << split.triangles_before << " -> " << split.triangles_after
        << " triangles, worst edge " << std::fixed << std::setprecision(2) << split.worst_before_px << " -> "
        << split.worst_after_px << " px from where the modules show it"
        << (split.capped ? " (stopped at the triangle budget: above the 0.5 px bound)" : "") << "\n";
  out << output.rendered_views() << " of " << output.views() << " " << what << " rendered";
  if (output.rendered_views() < output.views())
    out << " (" << output.views() - output.rendered_views() << " see nothing of the scene and show the background)";
  out << (options.view_probe ? "; view probe: view k drawn as grey level k" : "") << "\n";
  if (!frame_ms.empty()) {
    std::sort(frame_ms.begin(), frame_ms.end());
    const double median = frame_ms[frame_ms.size() / 2];
    out << "frame (CPU clock around glFinish), median of " << frame_ms.size() << ": " << std::fixed << std::setprecision(3)
        << median << " ms, " << median / std::max(1, output.rendered_views()) << " ms per rendered view\n";
  }
  out << "wrote " << options.output << " (" << (quilt ? "quilt" : "montage") << ", " << output_size.x << "x" << output_size.y
      << ")\n";
  if (!options.modules_dir.empty()) out << "wrote " << output.views() << " images to " << options.modules_dir << "\n";
  if (!options.native_output.empty())
    out << "wrote " << options.native_output << " (native panel image, " << output.native_size().x << "x"
        << output.native_size().y << ")\n";
  if (!options.dump_dir.empty() && !options.view_probe)
    out << "dumped each view's AO, position, normal, depth and view.json to " << options.dump_dir << "\n";
  return 0;
}

}  // namespace app
