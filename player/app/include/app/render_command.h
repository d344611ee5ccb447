#pragma once
// The player's sub-commands over the render pipeline: `render` (one scene to an image, per-pass
// times, optional dump for independent evaluation) and `info` (platform and GL capabilities).
#include "gl/caps.h"
#include "playback/timeline.h"
#include "render/renderer.h"
#include "scene/camera.h"
#include "scene/gltf_loader.h"

#include <iosfwd>
#include <string>
#include <vector>

namespace app {

struct RenderOptions {
  std::string scene;        // a .gltf/.glb path or builtin:NAME
  std::string environment;  // --environment: an equirectangular HDR/EXR, or builtin:studio (empty: the studio)
  std::string output;       // PNG path
  std::string platform = "auto";
  std::string dump_dir;           // empty: no dump
  int frames = 1;                 // frames rendered; times are the median over all but the first
  int file_camera = -1;           // >= 0: view through the scene's camera of that index (--file-camera)
  double time = 0.0;              // --time: seconds into the scene's animations, the pose shown
  std::string animation = "all";  // --animation: all, none, an index or a name
  // Light field output (--display): a display file; per-view PNGs; a quilt's panel image; the probe.
  std::string display, modules_dir, native_output;
  bool view_probe = false;
  std::string shader_cache;      // --shader-cache: a folder, "off", or empty for the default
  bool estimator_given = false;  // --estimator was on the command line (not the default)
  scene::Framing framing;
  render::FrameSettings frame;
};

// How scenes load on this context: textures beyond its largest texture are drawn white with a warning.
scene::LoadOptions load_options_for(const gl::Caps& caps);

// The framing a playback camera asks for (shared by `render` and `play`).
scene::Framing framing_of(const playback::Camera& camera);

// The view a playback camera asks for on a `width` x `height` surface: the scene's own camera when
// it names one (motion = "file") that the scene has and that is perspective, else the framing.
// `note`, when given, says why a named camera was not used (left empty when it was, or none was
// named); without it nothing is allocated, so the frame loop may call this every frame.
scene::Camera camera_for(const playback::Camera& camera, const scene::Bounds& bounds,
                         const std::vector<scene::FileCamera>& cameras, int width, int height, std::string* note = nullptr);
// The still camera of `player render` (its framing options, or --file-camera), for a view of
// width x height; `note` says why a file camera was not used.
scene::Camera render_camera(const RenderOptions& options, const scene::Scene& scene, int width, int height,
                            std::string* note = nullptr);

int run_render(const RenderOptions& options, std::ostream& out, std::ostream& err);
int run_info(const std::string& platform_name, const std::string& shader_cache, std::ostream& out, std::ostream& err);

}  // namespace app
