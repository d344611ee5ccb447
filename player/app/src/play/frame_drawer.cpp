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

FrameDrawer::FrameDrawer(gl::Session& session, const render::FrameSettings& base) : session_(session), base_(base) {}

bool FrameDrawer::configure_rotation(std::string& error) {
  surface_ = {session_.platform().framebuffer(), 0, 0, session_.platform().srgb_framebuffer()};
  const platform::Size size = session_.platform().size();
  if (!rotation_.configure(programs_, rotation_degrees_, size.width, size.height, surface_.srgb, error)) return false;
  present_ = rotation_.target(surface_);
  return true;
}

bool FrameDrawer::open(int rotation_degrees, std::string& error) {
  rotation_degrees_ = rotation_degrees;
  if (!programs_.build(session_, error) || !configure_rotation(error)) return false;
  for (ssao::Estimator estimator : ssao::kEstimators)
    for (ssao::Precision precision : ssao::kPrecisions)
      if (!programs_.ssao(estimator, precision, error)) return false;
  timer_.create(session_.caps().timer_query, false);
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
  constexpr int kPictures = static_cast<int>(std::size(render::kPictureNames));
  settings.output = static_cast<render::Picture>((static_cast<int>(settings.output) + output_offset_) % kPictures);
  return settings;
}

void FrameDrawer::prepare(const playback::Cue& cue, const std::string& key, const CachedScene& scene, const playback::Item& item,
                          StatusReporter& status) {
  gpu_ = scene.gpu.get();
  const lightfield::Display* display = scene.display.get();
  const bool new_item = cue.item != configured_item_ || cue.sequence != configured_sequence_ || key != shown_key_;
  if (new_item || cue.cut) {
    std::string error;
    output_ = &view_output_;
    if (display != nullptr) {
      light_field_.show_on(*display);
      output_ = &light_field_;
    }
    configured_ok_ = output_->configure(settings_for(item), *gpu_, present_.srgb, error);
    if (!configured_ok_)
      status.report(ErrorKind::content, key + ": " + error);
    else if (!output_->adjustment().empty())
      status.note(key + ": " + output_->adjustment());
    std::string camera_note;  // once per configuration: the frames that follow aim without a word
    const glm::ivec2 view = output_->view_size();
    camera_for(cue.camera, scene.bounds, scene.cameras, view.x, view.y, &camera_note);
    if (!camera_note.empty()) status.note(key + ": " + camera_note);
    configured_item_ = cue.item;
    configured_sequence_ = cue.sequence;
    shown_key_ = key;
  }
  // An item its output cannot show is the background until something configures it again.
  if (!configured_ok_) gpu_ = nullptr;
  if (gpu_ == nullptr) return;
  const glm::ivec2 size = output_->view_size();
  output_->aim(camera_for(cue.camera, scene.bounds, scene.cameras, size.x, size.y));
}

void FrameDrawer::draw(float fade) {
  if (gpu_ != nullptr) {
    // A light field output does not time its views by pass: the frame's pass times are the view's.
    const bool timed = output_ == &view_output_;
    const render::OutputFrame frame{*gpu_, fade, timed ? &timer_ : nullptr, &gl_error_};
    output_->render(frame);
    output_->present(frame, present_, rotation_.width(), rotation_.height());
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
  if (timer_.poll(times) && gpu_ != nullptr && scene_timed && output_ == &view_output_)
    render::note_raster_time(view_output_.targets(), render::to_pass_times(times, timer_.gpu_timed()));
  if (!gl_error_.empty()) {
    status.report(ErrorKind::gpu, "GL: " + gl_error_);
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
  const platform::Size size = session_.platform().size();
  const std::vector<uint8_t> rgba = render::read_presented(surface_, size.width, size.height);
  return write_png(path, size.width, size.height, rgba, error);
}

}  // namespace app
