#include "play/frame_drawer.h"

#include "app/render_command.h"
#include "gl/gl_api.h"
#include "image_io.h"
#include "play/scene_cache.h"
#include "play/status_reporter.h"
#include "render/readback.h"
#include "render/renderer.h"
#include "scene/camera.h"

#include <iterator>

namespace app {

FrameDrawer::FrameDrawer(platform::Platform& platform, const gl::Caps& caps, const render::FrameSettings& base)
    : platform_(platform), caps_(caps), base_(base) {}

bool FrameDrawer::configure_rotation(std::string& error) {
  surface_ = {platform_.framebuffer(), 0, 0, platform_.srgb_framebuffer()};
  const platform::Size size = platform_.size();
  if (!rotation_.configure(programs_, rotation_degrees_, size.width, size.height, surface_.srgb, error)) return false;
  present_ = rotation_.target(surface_);
  return true;
}

bool FrameDrawer::open(int rotation_degrees, std::string& error) {
  rotation_degrees_ = rotation_degrees;
  if (!configure_rotation(error) || !programs_.build(caps_, error)) return false;
  for (ssao::Estimator estimator : ssao::kEstimators)
    for (ssao::Precision precision : ssao::kPrecisions)
      if (!programs_.ssao(estimator, precision, error)) return false;
  timer_.create(caps_.timer_query, false);
  return true;
}

void FrameDrawer::show_overlay(bool on, size_t leds) {
  overlay_on_ = on;
  lamps_.resize(leds);
}

bool FrameDrawer::resized(std::string& error) {
  configured_item_ = -2;
  return configure_rotation(error);
}

void FrameDrawer::toggle_ao(bool settings_ao) {
  ao_on_ = ao_override_ ? !ao_on_ : !settings_ao;
  ao_override_ = true;
  configured_item_ = -2;
}

void FrameDrawer::next_output() {
  ++output_offset_;
  configured_item_ = -2;
}

render::FrameSettings FrameDrawer::settings_for(const playback::Item& item) const {
  render::FrameSettings settings = base_;
  settings.width = rotation_.width();
  settings.height = rotation_.height();
  std::string ignored;  // validated when the playlist was read
  for (const playback::Setting& setting : item.settings) render::apply_setting(settings, setting.key, setting.value, ignored);
  if (item.has_background) settings.background = item.background;
  if (ao_override_) settings.ao = ao_on_;
  constexpr int kOutputs = static_cast<int>(std::size(render::kOutputNames));
  settings.output = static_cast<render::Output>((static_cast<int>(settings.output) + output_offset_) % kOutputs);
  return settings;
}

void FrameDrawer::prepare(const playback::Cue& cue, const std::string& key, const CachedScene& scene, const playback::Item& item,
                          StatusReporter& status) {
  gpu_ = scene.gpu.get();
  const lightfield::Display* display = scene.display.get();
  const bool new_item = cue.item != configured_item_ || cue.sequence != configured_sequence_ || key != shown_key_;
  if (new_item || cue.cut) {
    std::string error;
    render::FrameSettings settings = settings_for(item);
    if (display != nullptr && display->type == lightfield::DisplayType::modules &&
        settings.ao_settings.estimator == ssao::Estimator::horizon) {
      // Horizon searches screen-space slices; Algorithm 2 for modules runs the hemisphere estimator.
      settings.ao_settings.estimator = ssao::Estimator::hemisphere;
    }
    const bool configured = display != nullptr ? light_field_.configure(programs_, caps_, *display, settings, scene.bounds,
                                                                        gpu_->radius(), light_field_targets_, error)
                                               : targets_.configure(programs_, caps_, settings, gpu_->radius(), present_.srgb, error);
    if (!configured) {
      status.report(key + ": " + error);
      gpu_ = nullptr;
    }
    configured_item_ = cue.item;
    configured_sequence_ = cue.sequence;
    shown_key_ = key;
  }
  shown_display_ = gpu_ != nullptr && display != nullptr;
  if (gpu_ == nullptr) return;
  if (shown_display_) {
    const glm::ivec2 size = light_field_.view_size();
    light_field_.set_camera(scene::frame(scene.bounds, framing_of(cue.camera), size.x, size.y));
  } else {
    view_ = render::view_of(scene::frame(scene.bounds, framing_of(cue.camera), targets_.settings().width, targets_.settings().height));
  }
}

void FrameDrawer::draw(float fade) {
  if (gpu_ != nullptr && shown_display_) {
    // Every module or view, then what the display is fed (a quilt's panel image, the modules'
    // montage) scaled onto the surface. Per-pass times are per view here: the frame is not timed by pass.
    light_field_.render(programs_, *gpu_, light_field_targets_, fade, false, {}, &gl_error_);
    light_field_.present(programs_, present_, rotation_.width(), rotation_.height());
  } else if (gpu_ != nullptr) {
    const render::PassContext pass{programs_, *gpu_, targets_, view_, &timer_, &gl_error_};
    render::render_view(pass, present_, fade);
  } else {
    gl::api.BindFramebuffer(GL_FRAMEBUFFER, present_.framebuffer);
    gl::api.Viewport(0, 0, rotation_.width(), rotation_.height());
    const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    gl::api.ClearBufferfv(GL_COLOR, 0, black);
  }
}

void FrameDrawer::end_frame(bool scene_timed, StatusReporter& status) {
  timer_.end_frame();
  // Pass times arrive a frame or two late; the automatic prepass choice is made from them.
  gl::FrameTimer::Times times;
  if (timer_.poll(times) && gpu_ != nullptr && scene_timed && !shown_display_)
    render::note_raster_time(targets_, render::to_pass_times(times, timer_.gpu_timed()));
  if (!gl_error_.empty()) {
    status.report("GL: " + gl_error_);
    gl_error_.clear();
  }
}

void FrameDrawer::draw_overlay(std::string_view state, const hal::Status& board) {
  if (!overlay_on_) return;
  for (size_t led = 0; led < lamps_.size(); ++led)
    lamps_[led] = {board.led_name(led), hal::to_string(board.pattern(led)), board.level(led)};
  overlay_.update(state, lamps_, present_.srgb);
  overlay_.draw(present_.framebuffer, rotation_.height());
}

bool FrameDrawer::write_frame(const std::string& path, std::string& error) const {
  const std::vector<uint8_t> rgba = render::read_presented(present_, rotation_.width(), rotation_.height());
  return write_png(path, rotation_.width(), rotation_.height(), rgba, error);
}

bool FrameDrawer::write_surface(const std::string& path, std::string& error) const {
  const platform::Size size = platform_.size();
  const std::vector<uint8_t> rgba = render::read_presented(surface_, size.width, size.height);
  return write_png(path, size.width, size.height, rgba, error);
}

}  // namespace app
