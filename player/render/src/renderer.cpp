#include "render/renderer.h"

#include <algorithm>

namespace render {

PassTimes to_pass_times(const gl::FrameTimer::Times& times, bool gpu_timed) {
  PassTimes result;
  for (int pass = 0; pass < kPassCount; ++pass) result.ms[static_cast<size_t>(pass)] = times[static_cast<size_t>(pass)];
  result.gpu_timed = gpu_timed;
  return result;
}

void note_raster_time(ViewTargets& targets, const PassTimes& times) {
  if (targets.settings().prepass != Prepass::automatic || times[Pass::gbuffer] < 0.0) return;
  // Times arrive frames late; whether that frame drew the prepass is in the times themselves.
  const bool with_prepass = times[Pass::depth_prepass] >= 0.0;
  double& slot = with_prepass ? targets.raster_with : targets.raster_without;
  if (slot < 0.0) slot = std::max(0.0, times[Pass::depth_prepass]) + times[Pass::gbuffer];
}

bool Renderer::init(gl::Session& session, const PresentTarget& target, std::string& error, bool serialise_timing) {
  caps_ = session.caps();
  target_ = target;
  if (!programs_.build(session, error)) return false;
  timer_.create(caps_.timer_query, serialise_timing);
  return true;
}

bool Renderer::upload(const scene::Scene& scene, std::string& error) {
  return scene_.upload(scene, caps_, error);
}

bool Renderer::configure(const FrameSettings& settings, std::string& error) {
  gl_error_.clear();
  return output_.configure(settings, scene_, target_.srgb, error);
}

void Renderer::render(const View& view, float fade) {
  inverse_far_ = static_cast<float>(1.0 / view.far);
  timer_.begin_frame();
  output_.aim(view);
  const OutputFrame frame{scene_, fade, &timer_, &gl_error_};
  output_.render(frame);
  output_.present(frame, target_, settings().width, settings().height);
  timer_.end_frame();
}

PassTimes Renderer::collect_times() {
  gl::FrameTimer::Times times;
  times.fill(-1.0);
  timer_.wait(times);
  const PassTimes result = to_pass_times(times, timer_.gpu_timed());
  note_raster_time(targets(), result);
  return result;
}

std::vector<uint8_t> Renderer::read_color() const {
  return read_presented(target_, settings().width, settings().height);
}

std::vector<glm::vec2> Renderer::read_ao_raw() const {
  return read_ao(targets().ao_raw, targets().ao_width(), targets().ao_height());
}

std::vector<glm::vec2> Renderer::read_ao_blurred() const {
  return read_ao(targets().ao_result(), targets().ao_width(), targets().ao_height());
}

std::vector<glm::vec2> Renderer::read_ao_final() const {
  return read_ao_full(programs_, targets());
}

}  // namespace render
