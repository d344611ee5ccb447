#include "render/light_field.h"

#include "gl/program.h"
#include "gl_util.h"
#include "render/readback.h"

#include <algorithm>
#include <cmath>

namespace render {
namespace {

float srgb_encode(float linear) {
  const float c = std::clamp(linear, 0.0f, 1.0f);
  return c < 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

}  // namespace

bool LightFieldRenderer::init(const gl::Caps& caps, std::string& error) {
  caps_ = caps;
  if (!programs_.build(caps, error)) return false;
  interleave_ = gl::build_program({{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "interleave.frag"}}, "", error);
  if (!interleave_) return false;
  detail::assign_units(interleave_, {"u_quilt"});
  interleave_constants_ = gl::uniform(interleave_, "u_constants");
  interleave_panel_ = gl::uniform(interleave_, "u_panel");
  interleave_layout_ = gl::uniform(interleave_, "u_layout");
  gl::api.UseProgram(0);
  return true;
}

bool LightFieldRenderer::upload(const scene::Scene& scene, std::string&) {
  bounds_ = scene.bounds;
  source_ = std::make_shared<const scene::Scene>(scene);
  uploaded_ = false;
  return true;
}

namespace {

// Whether two displays place vertices alike (the subdivided scene of one fits the other).
bool same_geometry(const lightfield::Display& a, const lightfield::Display& b) {
  if (a.type != b.type) return false;
  if (a.type == lightfield::DisplayType::quilt) return true;
  const lightfield::ModulesDisplay &x = a.modules, &y = b.modules;
  const auto same_box = [](const lightfield::Box& p, const lightfield::Box& q) { return p.min == q.min && p.max == q.max; };
  return x.screen_width == y.screen_width && x.screen_height == y.screen_height && x.observer_distance == y.observer_distance &&
         x.observer_height == y.observer_height && x.module_x == y.module_x && x.module_z == y.module_z && x.width == y.width &&
         x.height == y.height && x.footprint == y.footprint && same_box(x.physical_roi, y.physical_roi) &&
         x.world_roi.has_value() == y.world_roi.has_value() && (!x.world_roi || same_box(*x.world_roi, *y.world_roi));
}

}  // namespace

bool LightFieldRenderer::configure(const lightfield::Display& display, const FrameSettings& settings,
                                   const scene::Camera& camera, std::string& error) {
  display_ = display;
  settings_ = settings;
  const bool modules = display.type == lightfield::DisplayType::modules;
  if (modules) {
    settings_.width = display.modules.width;
    settings_.height = display.modules.height;
  } else {
    settings_.width = display.quilt.view_width;
    settings_.height = display.quilt.view_height;
  }
  // Views share one set of targets, so the prepass's automatic choice (measured per view over frames)
  // has nothing to measure: it stays off unless asked for.
  if (settings_.prepass == Prepass::automatic) settings_.prepass = Prepass::off;
  if (source_ == nullptr) {
    error = "no scene uploaded";
    return false;
  }
  if (!uploaded_ || !same_geometry(display, uploaded_for_)) {
    subdivision_ = SubdivisionReport{};
    const scene::Scene* to_upload = source_.get();
    scene::Scene subdivided;
    if (modules) {
      const lightfield::ModulesDisplay& m = display.modules;
      const auto roi = lightfield::roi_transform(lightfield::world_roi(m, {bounds_.min, bounds_.max}), m.physical_roi);
      if (roi) {
        subdivided = subdivide_for_modules(*source_, m, *roi, kMaxEdgeErrorPx, subdivision_);
        to_upload = &subdivided;
      }
    }
    if (!scene_.upload(*to_upload, caps_, error)) return false;
    uploaded_ = true;
    uploaded_for_ = display;
  }
  if (!targets_.configure(programs_, caps_, settings_, scene_.radius(), false, error, modules)) return false;

  const int count = display.views();
  views_.clear();
  views_.reserve(static_cast<size_t>(count));
  skipped_.assign(static_cast<size_t>(count), false);
  if (modules) {
    const lightfield::ModulesDisplay& m = display.modules;
    const lightfield::Box world = lightfield::world_roi(m, {bounds_.min, bounds_.max});
    const std::optional<lightfield::RoiTransform> roi = lightfield::roi_transform(world, m.physical_roi);
    if (!roi) {
      error = "display: roi: the world box and the physical box need a positive size along every axis";
      return false;
    }
    const lightfield::Box scene_box{roi->to_physical(bounds_.min), roi->to_physical(bounds_.max)};
    // One turn per world cell the size of a module pixel on the screen: neighbouring pixels still
    // differ (the blur averages them), and a point keeps its turn from module to module.
    const double seed_cell = (m.footprint.y - m.footprint.x) / m.width / roi->scale;
    for (int k = 0; k < count; ++k) {
      const lightfield::Module module = lightfield::module_of(m, k);
      views_.push_back(module_view(module, *roi, seed_cell));
      skipped_[static_cast<size_t>(k)] = !lightfield::sees(module, scene_box);
    }
    grid_ = lightfield::montage_grid(count);
  } else {
    const double aspect = static_cast<double>(settings_.width) / settings_.height;
    for (int k = 0; k < count; ++k) {
      // The outer views stand up to 1 / cos(cone / 2) farther from the scene than the centre one.
      const lightfield::OffAxisView v = lightfield::quilt_view(camera.eye, camera.target, camera.up, camera.fov_y, aspect,
                                                               camera.near * 0.8, camera.far * 1.25,
                                                               display.quilt.calibration.view_cone_deg, k, count);
      View view;
      view.view = v.view;
      view.projection = v.projection;
      view.near = camera.near * 0.8;
      view.far = camera.far * 1.25;
      view.eye = v.eye;
      views_.push_back(view);
    }
    grid_ = {display.quilt.columns, display.quilt.rows};
  }
  output_size_ = grid_ * glm::ivec2(settings_.width, settings_.height);
  if (output_size_.x > caps_.max_texture_size || output_size_.y > caps_.max_texture_size) {
    error = "display: the " + std::string(modules ? "montage" : "quilt") + " of " + std::to_string(count) + " views is " +
            std::to_string(output_size_.x) + "x" + std::to_string(output_size_.y) + ", beyond this GPU's " +
            std::to_string(caps_.max_texture_size) + " pixels per side";
    return false;
  }
  const auto make_output = [](gl::Texture& texture, gl::Framebuffer& fbo, glm::ivec2 size) {
    texture = detail::make_target(GL_RGBA8, size.x, size.y);
    fbo = gl::make_framebuffer();
    gl::api.BindFramebuffer(GL_FRAMEBUFFER, fbo.id());
    gl::api.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture.id(), 0);
    const GLenum status = gl::api.CheckFramebufferStatus(GL_FRAMEBUFFER);
    gl::api.BindFramebuffer(GL_FRAMEBUFFER, 0);
    return status == GL_FRAMEBUFFER_COMPLETE;
  };
  if (!make_output(output_texture_, output_fbo_, output_size_)) {
    error = "the light field output framebuffer is incomplete";
    return false;
  }
  native_texture_.reset();
  native_fbo_.reset();
  if (!modules) {
    const glm::ivec2 panel(display.quilt.calibration.screen_width, display.quilt.calibration.screen_height);
    if (panel.x > caps_.max_texture_size || panel.y > caps_.max_texture_size) {
      error = display.calibration_path + ": the panel (" + std::to_string(panel.x) + "x" + std::to_string(panel.y) +
              ") is beyond this GPU's " + std::to_string(caps_.max_texture_size) + " pixels per side";
      return false;
    }
    if (!make_output(native_texture_, native_fbo_, panel)) {
      error = "the native panel framebuffer is incomplete";
      return false;
    }
  }
  const GLenum status = gl::api.GetError();
  if (status != GL_NO_ERROR) {
    error = "allocating the light field outputs raised GL error 0x" + std::to_string(status);
    return false;
  }
  gl_error_.clear();
  return true;
}

glm::ivec2 LightFieldRenderer::tile_origin(int k) const {
  const glm::ivec2 size(settings_.width, settings_.height);
  if (quilt()) return lightfield::tile_of(display_.quilt, k) * size;
  // The montage reads like a page: module 0 at the top left.
  return glm::ivec2(k % grid_.x, grid_.y - 1 - k / grid_.x) * size;
}

glm::ivec2 LightFieldRenderer::native_size() const {
  return quilt() ? glm::ivec2(display_.quilt.calibration.screen_width, display_.quilt.calibration.screen_height) : glm::ivec2(0);
}

void LightFieldRenderer::set_pixel_turns(bool pixel_turns) {
  for (View& view : views_)
    if (view.module) view.module->pixel_turns = pixel_turns;
}

int LightFieldRenderer::rendered_views() const {
  return static_cast<int>(std::count(skipped_.begin(), skipped_.end(), false));
}

void LightFieldRenderer::render(bool probe, const AfterView& after_view) {
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, output_fbo_.id());
  gl::api.Viewport(0, 0, output_size_.x, output_size_.y);
  const glm::vec3 background = settings_.background;
  const float clear[4] = {srgb_encode(background.r), srgb_encode(background.g), srgb_encode(background.b), 1.0f};
  gl::api.ClearBufferfv(GL_COLOR, 0, clear);
  for (int k = 0; k < views(); ++k) {
    if (skipped_[static_cast<size_t>(k)]) continue;
    const glm::ivec2 origin = tile_origin(k);
    if (probe) {
      gl::api.BindFramebuffer(GL_FRAMEBUFFER, output_fbo_.id());
      gl::api.Enable(GL_SCISSOR_TEST);
      gl::api.Scissor(origin.x, origin.y, settings_.width, settings_.height);
      const float level = static_cast<float>(k) / 255.0f;
      const float flat[4] = {level, level, level, 1.0f};
      gl::api.ClearBufferfv(GL_COLOR, 0, flat);
      gl::api.Disable(GL_SCISSOR_TEST);
      continue;
    }
    const Frame frame{programs_, scene_, targets_, views_[static_cast<size_t>(k)], nullptr, &gl_error_};
    render_view(frame, PresentTarget{output_fbo_.id(), origin.x, origin.y, false}, 1.0f);
    if (after_view) after_view(k, views_[static_cast<size_t>(k)], targets_);
  }
  if (quilt()) {
    const lightfield::Calibration& c = display_.quilt.calibration;
    const lightfield::Interleave interleave = lightfield::interleave_of(c, views());
    gl::api.BindFramebuffer(GL_FRAMEBUFFER, native_fbo_.id());
    gl::api.Viewport(0, 0, c.screen_width, c.screen_height);
    gl::api.Disable(GL_DEPTH_TEST);
    gl::api.UseProgram(interleave_.id());
    gl::api.Uniform4f(interleave_constants_, static_cast<float>(interleave.pitch), static_cast<float>(interleave.tilt),
                      static_cast<float>(interleave.subpixel), static_cast<float>(interleave.center));
    gl::api.Uniform4i(interleave_panel_, c.screen_width, c.screen_height, c.inverted_views ? 1 : 0, c.flip_y ? 1 : 0);
    gl::api.Uniform4i(interleave_layout_, grid_.x, grid_.y, settings_.width, settings_.height);
    detail::bind_texture(0, output_texture_);
    gl::api.BindVertexArray(programs_.empty_vertex_array.id());
    gl::api.DrawArrays(GL_TRIANGLES, 0, 3);
    gl::api.BindVertexArray(0);
  }
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

std::vector<uint8_t> LightFieldRenderer::read_output() const {
  return read_presented(PresentTarget{output_fbo_.id(), 0, 0, false}, output_size_.x, output_size_.y);
}

std::vector<uint8_t> LightFieldRenderer::read_view(int k) const {
  const glm::ivec2 origin = tile_origin(k);
  return read_presented(PresentTarget{output_fbo_.id(), origin.x, origin.y, false}, settings_.width, settings_.height);
}

std::vector<uint8_t> LightFieldRenderer::read_native() const {
  const glm::ivec2 size = native_size();
  return read_presented(PresentTarget{native_fbo_.id(), 0, 0, false}, size.x, size.y);
}

}  // namespace render
