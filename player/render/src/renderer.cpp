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
  if (targets.settings().prepass != Prepass::automatic || times.ms[kGBuffer] < 0.0) return;
  // Times arrive frames late; whether that frame drew the prepass is in the times themselves.
  const bool with_prepass = times.ms[kDepthPrepass] >= 0.0;
  double& slot = with_prepass ? targets.raster_with : targets.raster_without;
  if (slot < 0.0) slot = std::max(0.0, times.ms[kDepthPrepass]) + times.ms[kGBuffer];
}

bool Renderer::init(const gl::Caps& caps, const PresentTarget& target, std::string& error, bool serialise_timing) {
  caps_ = caps;
  target_ = target;
  if (!programs_.build(caps, error)) return false;
  timer_.create(caps.timer_query, serialise_timing);
  return true;
}

bool Renderer::upload(const scene::Scene& scene, std::string& error) { return scene_.upload(scene, caps_, error); }

bool Renderer::configure(const FrameSettings& settings, std::string& error) {
  gl_error_.clear();
  return targets_.configure(programs_, caps_, settings, scene_.radius(), target_.srgb, error);
}

void Renderer::render(const View& view, float fade) {
  view_ = view;
  inverse_far_ = static_cast<float>(1.0 / view.far);
  timer_.begin_frame();
  const PassContext context{programs_, scene_, targets_, view_, &timer_, &gl_error_};
  render_view(context, target_, fade);
  timer_.end_frame();
}

PassTimes Renderer::collect_times() {
  gl::FrameTimer::Times times;
  times.fill(-1.0);
  timer_.wait(times);
  const PassTimes result = to_pass_times(times, timer_.gpu_timed());
  note_raster_time(targets_, result);
  return result;
}

std::vector<uint8_t> Renderer::read_color() const {
  return read_presented(target_, targets_.settings().width, targets_.settings().height);
}

std::vector<glm::vec2> Renderer::read_ao_raw() const { return read_ao(targets_.ao_raw, targets_.ao_width(), targets_.ao_height()); }

std::vector<glm::vec2> Renderer::read_ao_blurred() const {
  return read_ao(targets_.ao_result(), targets_.ao_width(), targets_.ao_height());
}

std::vector<glm::vec2> Renderer::read_ao_final() const { return read_ao_full(programs_, targets_); }

}  // namespace render
