// aobench --ghosting. For each animated scene and each of a few poses spread over its loop, with a
// still camera, four AO images of the same pose at the same pixels:
//   accumulated  the default temporal AO after `frames` frames played up to the pose (motion vectors);
//   camera-only  the same with motion-vectors=off (history found where the camera alone puts it);
//   one frame    temporal off: a single frame's AO at the pose;
//   converged    the pose frozen and `converged` frames averaged: what the estimator tends to there.
// The reference is the converged SSAO, not a ray-traced one: ghosting is the temporal pass's error,
// and the estimator's own bias, which every one of the images shares, would only dilute it. Errors
// are mean absolute differences over the pixels that moved in the last frame (the motion target: by
// more than a thousandth of their distance), and over the still rest of the scene.
#include "ghosting.h"

#include "gl/caps.h"
#include "gl/session.h"
#include "platform/platform.h"
#include "render/renderer.h"
#include "scene/animation.h"
#include "scene/camera.h"
#include "scene/load.h"

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>

namespace aobench {
namespace {

namespace fs = std::filesystem;

// The samples with skins, morph targets or moving nodes, where a checkout has ../shared beside it.
constexpr const char* kDefaultScenes[] = {"../shared/samples/khronos/CesiumMan/CesiumMan.glb",
                                          "../shared/samples/khronos/Fox/Fox.glb",
                                          "../shared/samples/khronos/BoxAnimated/BoxAnimated.glb",
                                          "../shared/samples/khronos/AnimatedMorphSphere/AnimatedMorphSphere.glb",
                                          "../shared/samples/khronos/CesiumMilkTruck/CesiumMilkTruck.glb"};

constexpr size_t kMinMovingPixels = 256;
constexpr double kMinError = 1e-4;

struct Errors {
  double moving = 0.0, still = 0.0;
  size_t moving_pixels = 0, still_pixels = 0;
};

// Mean |a - b| over the object pixels, split by `moving`.
Errors mean_difference(const std::vector<glm::vec2>& a, const std::vector<glm::vec2>& b, const std::vector<float>& depth,
                       const std::vector<bool>& moving) {
  Errors errors;
  for (size_t i = 0; i < depth.size(); ++i) {
    if (depth[i] <= 0.0f) continue;
    const double difference = std::abs(static_cast<double>(a[i].x) - static_cast<double>(b[i].x));
    if (moving[i]) {
      errors.moving += difference;
      ++errors.moving_pixels;
    } else {
      errors.still += difference;
      ++errors.still_pixels;
    }
  }
  if (errors.moving_pixels) errors.moving /= static_cast<double>(errors.moving_pixels);
  if (errors.still_pixels) errors.still /= static_cast<double>(errors.still_pixels);
  return errors;
}

}  // namespace

int run_ghosting(GhostingOptions options) {
  if (options.scenes.empty())
    for (const char* path : kDefaultScenes)
      if (fs::exists(path)) options.scenes.emplace_back(path);
  if (options.scenes.empty()) {
    std::cerr << "error: --ghosting: no --scene given and no animated sample found under ../shared/samples/khronos\n";
    return 1;
  }
  std::string error;
  platform::Options platform_options;
  platform_options.name = options.platform;
  platform_options.size = {options.width, options.height};
  const auto session = gl::Session::open(platform_options, error);
  if (!session) {
    std::cerr << "error: " << error << "\n";
    return 1;
  }
  const platform::Platform& platform = session->platform();
  std::cout << "aobench --ghosting: " << options.scenes.size() << " scenes x " << options.poses << " poses at " << options.width
            << "x" << options.height << " on " << platform.name() << " (" << session->caps().renderer << "); " << options.frames
            << " frames at " << options.fps << " fps up to each pose, reference: " << options.converged
            << " frames at the frozen pose\n"
            << "error = mean |AO - converged| over the pixels that moved (and over the still rest); goal: accumulated <= "
            << options.goal << " x one frame\n\n";
  std::cout << std::left << std::setw(28) << "scene" << std::setw(8) << "time" << std::setw(10) << "moving" << std::setw(11)
            << "one frame" << std::setw(13) << "accumulated" << std::setw(13) << "camera-only" << std::setw(8) << "ratio"
            << std::setw(13) << "still: one" << std::setw(13) << "accumulated"
            << "\n";

  double ratio_sum = 0.0, camera_ratio_sum = 0.0;
  int measured = 0, over_goal = 0;
  for (const std::string& spec : options.scenes) {
    scene::Scene scene;
    if (!scene::load(spec, scene, error, std::cerr)) {
      std::cerr << "error: " << error << "\n";
      return 1;
    }
    if (!scene.rig || scene.rig->animations.empty()) {
      std::cerr << "error: " << spec << ": has no animation to measure ghosting on\n";
      return 1;
    }
    const std::shared_ptr<const scene::Rig> rig = scene.rig;
    render::Renderer renderer;
    const render::PresentTarget target{platform.framebuffer(), 0, 0, platform.srgb_framebuffer()};
    render::FrameSettings accumulating;
    accumulating.width = options.width;
    accumulating.height = options.height;
    accumulating.reuse_static_ao = false;
    if (!renderer.init(*session, target, error) || !renderer.upload(scene, error) || !renderer.configure(accumulating, error)) {
      std::cerr << "error: " << spec << ": " << error << "\n";
      return 1;
    }
    const scene::Camera camera = scene::frame(scene.bounds, scene::Framing{}, options.width, options.height);
    scene::Pose pose(rig);
    const double duration = rig->duration(scene::Rig::kAllAnimations);
    // Plays `frames` frames that end at `time` (all at `time` when `frozen`) and returns the AO shown.
    auto play = [&](const render::FrameSettings& settings, double time, int frames, bool frozen) {
      if (!renderer.configure(settings, error)) return std::vector<glm::vec2>();
      for (int frame = 0; frame < frames; ++frame) {
        pose.at(scene::Rig::kAllAnimations, frozen ? time : time - (frames - 1 - frame) / options.fps);
        renderer.pose(pose);
        renderer.render(camera);
      }
      return renderer.read_ao_final();
    };
    for (int p = 0; p < options.poses; ++p) {
      const double time = duration * (p + 0.5) / options.poses + static_cast<double>(options.frames) / options.fps;
      const std::vector<glm::vec2> accumulated = play(accumulating, time, options.frames, false);
      if (accumulated.empty()) {
        std::cerr << "error: " << spec << ": " << error << "\n";
        return 1;
      }
      const std::vector<glm::vec3> motion = render::read_motion(renderer.targets());
      const std::vector<float> depth = renderer.read_linear_depth();
      if (motion.size() != depth.size()) {
        std::cerr << "error: " << spec << ": the G-buffer has no motion target (motion-vectors off?)\n";
        return 1;
      }
      std::vector<bool> moving(depth.size());
      for (size_t i = 0; i < depth.size(); ++i) moving[i] = glm::length(motion[i]) > 1e-3f * depth[i];
      render::FrameSettings camera_only = accumulating;
      camera_only.motion_vectors = false;
      const std::vector<glm::vec2> camera_reprojected = play(camera_only, time, options.frames, false);
      render::FrameSettings single = accumulating;
      single.temporal = false;
      const std::vector<glm::vec2> one_frame = play(single, time, 1, true);
      render::FrameSettings converging = accumulating;
      converging.history = 255;
      const std::vector<glm::vec2> converged = play(converging, time, options.converged, true);
      if (camera_reprojected.empty() || one_frame.empty() || converged.empty()) {
        std::cerr << "error: " << spec << ": " << error << "\n";
        return 1;
      }
      const Errors one = mean_difference(one_frame, converged, depth, moving);
      const Errors acc = mean_difference(accumulated, converged, depth, moving);
      const Errors cam = mean_difference(camera_reprojected, converged, depth, moving);
      const std::string name = fs::path(spec).stem().string();
      std::cout << std::left << std::setw(28) << name.substr(0, 27) << std::setw(8) << std::setprecision(3)
                << std::fmod(time, duration) << std::setw(10) << one.moving_pixels;
      if (one.moving_pixels == 0) {
        std::cout << "(nothing moved at this pose)\n";
        continue;
      }
      // A ratio of errors at float rounding's level (parts with no AO on them), or over a handful of
      // pixels, says nothing about ghosting: shown, not counted.
      const bool measurable = one.moving_pixels >= kMinMovingPixels && one.moving >= kMinError;
      const double ratio = acc.moving / one.moving, camera_ratio = cam.moving / one.moving;
      std::cout << std::setprecision(4) << std::setw(11) << one.moving << std::setw(13) << acc.moving << std::setw(13)
                << cam.moving << std::setw(8) << std::setprecision(3) << ratio << std::setprecision(4) << std::setw(13)
                << one.still << std::setw(13) << acc.still
                << (!measurable            ? "  (too little AO or too few pixels to count)"
                    : ratio > options.goal ? "  over the goal"
                                           : "")
                << "\n";
      if (!measurable) continue;
      ratio_sum += ratio;
      camera_ratio_sum += camera_ratio;
      ++measured;
      if (ratio > options.goal) ++over_goal;
    }
  }
  if (measured == 0) {
    std::cout << "\nno pose had moving pixels\n";
    return 0;
  }
  std::cout << "\nmean ratio over " << measured << " poses: accumulated / one frame " << std::setprecision(3)
            << ratio_sum / measured << " (camera-only reprojection " << camera_ratio_sum / measured << "); " << over_goal
            << " over the goal of " << options.goal << "\n";
  return 0;
}

}  // namespace aobench
