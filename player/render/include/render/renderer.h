#pragma once
// One view of one scene, for the commands and tests that render a single image: the programs, the
// scene's GPU data, a view output (output.h) and a frame timer, put together.
#include "gl/caps.h"
#include "gl/frame_timer.h"
#include "gl/session.h"
#include "render/output.h"
#include "render/passes.h"
#include "render/programs.h"
#include "render/readback.h"
#include "render/scene_gpu.h"
#include "render/settings.h"
#include "render/uniform_blocks.h"
#include "render/view.h"
#include "render/view_targets.h"

#include <algorithm>
#include <array>
#include <string>
#include <vector>

namespace render {

struct PassTimes {
  std::array<double, kPassCount> ms{};  // by Pass; negative: the pass did not run
  bool gpu_timed = false;               // false: CPU time around glFinish
  double operator[](Pass pass) const { return ms[static_cast<size_t>(pass)]; }
};

class Renderer {
 public:
  Renderer() = default;
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Builds the programs in `session` (which outlives the renderer); `target` is where frames are
  // presented. `serialise_timing`: without timer queries, time passes around glFinish (render
  // command, benchmarks; never the player loop).
  bool init(gl::Session& session, const PresentTarget& target, std::string& error, bool serialise_timing = true);
  bool upload(const scene::Scene& scene, std::string& error);
  bool configure(const FrameSettings& settings, std::string& error);

  // One frame. Neither allocates nor throws; a GL error is recorded, not raised.
  void render(const View& view, float fade = 1.0f);
  void render(const scene::Camera& camera) { render(view_of(camera)); }

  // The last frame's pass times, waiting for them (outside the frame loop).
  PassTimes collect_times();
  // The first GL error seen since configure(), as "pass: GL error 0x...", or empty.
  const std::string& gl_error() const { return gl_error_; }

  std::vector<uint8_t> read_color() const;  // RGBA8, row 0 at the top
  std::vector<float> read_linear_depth() const { return render::read_linear_depth(targets()); }
  std::vector<glm::vec3> read_view_normals() const { return render::read_view_normals(targets()); }
  std::vector<glm::vec3> read_view_face_normals() const { return render::read_view_face_normals(targets()); }
  std::vector<glm::vec2> read_ao_raw() const;  // at the AO resolution (half with half_resolution)
  std::vector<glm::vec2> read_ao_blurred()
      const;  // ditto, what the present pass reads: blurred, else the temporal average, else raw
  std::vector<glm::vec2> read_ao_final() const;
  std::vector<float> read_history_frames() const {
    return render::read_history_frames(targets());
  }  // full resolution: what the present pass used

  const shared_layout::SsaoParams& ssao_params() const { return targets().ssao_params; }
  const shared_layout::BlurParams& blur_params(int direction) const { return targets().blur_params[direction]; }
  shared_layout::UpsampleParams upsample_params() const { return render::pack_upsample_params(targets()); }
  bool reused_ao() const { return targets().reused_ao; }
  // Frames the AO shown is the average of (1 without temporal accumulation).
  int ao_frames_averaged() const { return targets().temporal() ? std::max(targets().still_frames, 1) : 1; }
  bool prepass_in_use() const { return targets().prepass_now; }
  double raster_ms_with_prepass() const { return targets().raster_with; }
  double raster_ms_without_prepass() const { return targets().raster_without; }
  float base_radius() const { return targets().base_radius; }
  float inverse_far() const { return inverse_far_; }
  const FrameSettings& settings() const { return targets().settings(); }
  const View& last_view() const { return output_.view(); }

  Programs& programs() { return programs_; }
  const Programs& programs() const { return programs_; }
  const SceneGpu& scene() const { return scene_; }
  // The uploaded scene's draws placed at a pose of its rig (SceneGpu::pose).
  void pose(const scene::Pose& pose) { scene_.pose(pose); }
  ViewTargets& targets() { return output_.targets(); }
  const ViewTargets& targets() const { return output_.targets(); }

 private:
  gl::Caps caps_;
  PresentTarget target_;
  Programs programs_;
  SceneGpu scene_;
  ViewOutput output_{programs_, caps_};
  gl::FrameTimer timer_;
  float inverse_far_ = 0.0f;
  std::string gl_error_;
};

// Records the pass times of a frame from a FrameTimer into PassTimes; the prepass measurement of
// Prepass::automatic is fed from the same times.
PassTimes to_pass_times(const gl::FrameTimer::Times& times, bool gpu_timed);
void note_raster_time(ViewTargets& targets, const PassTimes& times);

}  // namespace render
