#pragma once
// Draws the cue's scene onto the platform's surface: the programs (every SSAO variant built at
// open), the targets configured for the item shown (its settings, the scene's radius, a light field
// display), the board's rotation, the button overrides of AO and output, the GPU pass times, the
// LED panel over a desktop window, and the frame files of --out and --snapshot.
#include "gl/caps.h"
#include "gl/frame_timer.h"
#include "gl/session.h"
#include "hal/status.h"
#include "overlay.h"
#include "platform/platform.h"
#include "playback/timeline.h"
#include "render/light_field.h"
#include "render/output.h"
#include "render/passes.h"
#include "render/programs.h"
#include "render/rotation.h"
#include "render/settings.h"
#include "render/view.h"
#include "render/view_targets.h"

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace app {

struct CachedScene;
class StatusReporter;

class FrameDrawer {
 public:
  // `base`: the command line's settings, which a playlist item's settings override. Both outlive the drawer.
  FrameDrawer(gl::Session& session, const render::FrameSettings& base);

  // Builds every program and SSAO variant now, so a playlist item with another estimator or
  // precision does not compile mid-play, and turns frames by `rotation_degrees`. False and why.
  bool open(int rotation_degrees, std::string& error);
  // The context's programs: how many were compiled and how many came from the shader cache.
  const gl::ProgramCache& programs() const { return session_.programs(); }
  // The LED panel over every frame (play --overlay).
  void show_overlay(bool on, size_t leds);

  // The surface changed size: the frame's size and target follow. False and why.
  bool resized(std::string& error);
  // The next frame configures its targets again (a new scene version, a display back, a button).
  void configure_again() { configured_item_ = -2; }
  // The key of the scene the targets are configured for.
  const std::string& shown_key() const { return shown_key_; }
  // Buttons: AO on or off against what the settings say; the next output (colour, AO, depth, ...).
  void toggle_ao(bool settings_ao);
  void next_output();

  // Readies `scene` (keyed `key`, the cue's item of `item` settings) for drawing: its targets are
  // configured anew when the item, its sequence or the scene changed, or the cue cut.
  void prepare(const playback::Cue& cue, const std::string& key, const CachedScene& scene, const playback::Item& item,
               StatusReporter& status);
  // Nothing to draw this frame: the background colour (loading, or nothing playable).
  void prepare_nothing() { gpu_ = nullptr; }

  // One frame: begin, then draw() or another picture (a self-check's) into present(), then end.
  void begin_frame() { timer_.begin_frame(); }
  void draw(float fade);
  // `scene_timed`: the frame was the scene's, so its pass times choose the prepass.
  void end_frame(bool scene_timed, StatusReporter& status);
  void draw_overlay(std::string_view state, const hal::Status& board);

  // Where frames are drawn, and their size (the surface turned by the rotation).
  const render::PresentTarget& present() const { return present_; }
  int width() const { return rotation_.width(); }
  int height() const { return rotation_.height(); }
  // The frame as drawn, to a PNG (--out). Then finish() turns it onto the surface.
  bool write_frame(const std::string& path, std::string& error) const;
  void finish() const { rotation_.finish(programs_, surface_); }
  // The surface as the GPU drew it, before it goes to the display (--snapshot).
  bool write_surface(const std::string& path, std::string& error) const;

 private:
  bool configure_rotation(std::string& error);
  render::FrameSettings settings_for(const playback::Item& item) const;

  gl::Session& session_;
  const render::FrameSettings& base_;
  render::Programs programs_;
  render::PresentTarget surface_{};  // the platform's framebuffer
  render::PresentTarget present_{};  // the surface, or the rotation's target
  render::Rotation rotation_;
  int rotation_degrees_ = 0;
  gl::FrameTimer timer_;

  // The item the targets are configured for.
  std::string shown_key_;
  int configured_item_ = -2;
  bool configured_ok_ = false;
  std::uint64_t configured_sequence_ = 0;
  const render::SceneGpu* gpu_ = nullptr;  // this frame's scene; null: the background
  // The item's output: the surface's own view, or a light field display's modules or views.
  render::ViewOutput view_output_{programs_, session_.caps()};
  render::LightFieldOutput light_field_{programs_, session_.caps()};
  render::Output* output_ = &view_output_;
  std::string gl_error_;

  // Button overrides.
  bool ao_override_ = false, ao_on_ = true;
  int output_offset_ = 0;

  Overlay overlay_;
  bool overlay_on_ = false;
  std::vector<Overlay::Lamp> lamps_;
};

}  // namespace app
