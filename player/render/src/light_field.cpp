#include "render/light_field.h"

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

scene::Scene prepare_for_display(const scene::Scene& scene, const lightfield::Display& display, SubdivisionReport& report) {
  report = SubdivisionReport{};
  if (display.type != lightfield::DisplayType::modules) return scene;
  const lightfield::ModulesDisplay& m = display.modules;
  const auto roi = lightfield::roi_transform(lightfield::world_roi(m, {scene.bounds.min, scene.bounds.max}), m.physical_roi);
  if (!roi) return scene;
  return subdivide_for_modules(scene, m, *roi, LightFieldRenderer::kMaxEdgeErrorPx, report);
}

bool LightFieldOutput::configure(const FrameSettings& frame_settings, const SceneGpu& scene, bool, std::string& error) {
  // The views render into the output texture, which holds sRGB-encoded bytes; present() decodes them
  // for a target that encodes itself.
  const lightfield::Display& display = display_;
  const scene::Bounds& bounds = scene.bounds();
  const gl::Caps& caps = caps_;
  FrameSettings settings = frame_settings;
  const bool modules = display.type == lightfield::DisplayType::modules;
  adjustment_.clear();
  if (modules && settings.ao_settings.estimator == ssao::Estimator::horizon) {
    settings.ao_settings.estimator = ssao::Estimator::hemisphere;
    adjustment_ =
        "estimator: hemisphere (horizon searches screen-space slices and has no form for optical modules; "
        "Algorithm 2 runs hemisphere)";
  }
  settings.width = modules ? display.modules.width : display.quilt.view_width;
  settings.height = modules ? display.modules.height : display.quilt.view_height;
  // Views share one set of targets, so the prepass's automatic choice (measured per view over frames)
  // has nothing to measure: it stays off unless asked for.
  if (settings.prepass == Prepass::automatic) settings.prepass = Prepass::off;
  // For the same reason there is no history to accumulate from: the previous frame of these targets
  // is another view's.
  settings.temporal = false;
  if (!targets_.configure(programs_, caps, settings, scene, false, error, modules) ||
      !prepare_material_programs(programs_, scene, targets_, false, error))
    return false;
  if (!programs_.build_interleave(error)) return false;  // also the copy present() uses
  background_ = settings.background;
  view_size_ = {settings.width, settings.height};

  const int count = display.views();
  views_.assign(static_cast<size_t>(count), View{});
  skipped_.assign(static_cast<size_t>(count), false);
  if (modules) {
    const lightfield::ModulesDisplay& m = display.modules;
    const std::optional<lightfield::RoiTransform> roi =
        lightfield::roi_transform(lightfield::world_roi(m, {bounds.min, bounds.max}), m.physical_roi);
    if (!roi) {
      error = "display: roi: the world box and the physical box need a positive size along every axis";
      return false;
    }
    const lightfield::Box scene_box{roi->to_physical(bounds.min), roi->to_physical(bounds.max)};
    // One turn per world cell the size of a module pixel on the screen: neighbouring pixels still
    // differ (the blur averages them), and a point keeps its turn from module to module.
    const double seed_cell = (m.footprint.y - m.footprint.x) / m.width / roi->scale;
    for (int k = 0; k < count; ++k) {
      const lightfield::Module module = lightfield::module_of(m, k);
      views_[static_cast<size_t>(k)] = module_view(module, *roi, seed_cell);
      skipped_[static_cast<size_t>(k)] = !lightfield::sees(module, scene_box);
    }
    grid_ = lightfield::montage_grid(count);
  } else {
    grid_ = {display.quilt.columns, display.quilt.rows};
  }
  output_size_ = grid_ * view_size_;
  if (output_size_.x > caps.max_texture_size || output_size_.y > caps.max_texture_size) {
    error = "display: the " + std::string(modules ? "montage" : "quilt") + " of " + std::to_string(count) + " views is " +
            std::to_string(output_size_.x) + "x" + std::to_string(output_size_.y) + ", beyond this GPU's " +
            std::to_string(caps.max_texture_size) + " pixels per side";
    return false;
  }
  const auto make_output = [](gl::Texture& texture, gl::Framebuffer& fbo, glm::ivec2 size) {
    texture = detail::make_target(GL_RGBA8, size.x, size.y);
    gl::api.BindTexture(GL_TEXTURE_2D, texture.id());
    gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);  // present() scales it
    gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl::api.BindTexture(GL_TEXTURE_2D, 0);
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
    const glm::ivec2 panel = native_size();
    if (panel.x > caps.max_texture_size || panel.y > caps.max_texture_size) {
      error = display.calibration_path + ": the panel (" + std::to_string(panel.x) + "x" + std::to_string(panel.y) +
              ") is beyond this GPU's " + std::to_string(caps.max_texture_size) + " pixels per side";
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
  return true;
}

void LightFieldOutput::aim(const scene::Camera& camera) {
  if (display_.type != lightfield::DisplayType::quilt) return;
  const double aspect = static_cast<double>(view_size_.x) / view_size_.y;
  // The outer views stand up to 1 / cos(cone / 2) farther from the scene than the centre one.
  const double near = camera.near * 0.8, far = camera.far * 1.25;
  for (int k = 0; k < views(); ++k) {
    const lightfield::OffAxisView v = lightfield::quilt_view(camera.eye, camera.target, camera.up, camera.fov_y, aspect, near,
                                                             far, display_.quilt.calibration.view_cone_deg, k, views());
    View& view = views_[static_cast<size_t>(k)];
    view.view = v.view;
    view.projection = v.projection;
    view.near = near;
    view.far = far;
    view.eye = v.eye;
  }
}

void LightFieldOutput::set_pixel_turns(bool pixel_turns) {
  for (View& view : views_)
    if (view.module) view.module->pixel_turns = pixel_turns;
}

glm::ivec2 LightFieldOutput::tile_origin(int k) const {
  if (quilt()) return lightfield::tile_of(display_.quilt, k) * view_size_;
  // The montage reads like a page: module 0 at the top left.
  return glm::ivec2(k % grid_.x, grid_.y - 1 - k / grid_.x) * view_size_;
}

glm::ivec2 LightFieldOutput::native_size() const {
  return quilt() ? glm::ivec2(display_.quilt.calibration.screen_width, display_.quilt.calibration.screen_height) : glm::ivec2(0);
}

int LightFieldOutput::rendered_views() const {
  return static_cast<int>(std::count(skipped_.begin(), skipped_.end(), false));
}

void LightFieldOutput::render(const OutputFrame& frame) {
  const float fade = frame.fade;
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, output_fbo_.id());
  gl::api.Viewport(0, 0, output_size_.x, output_size_.y);
  const float clear[4] = {srgb_encode(background_.r * fade), srgb_encode(background_.g * fade), srgb_encode(background_.b * fade),
                          1.0f};
  gl::api.ClearBufferfv(GL_COLOR, 0, clear);
  for (int k = 0; k < views(); ++k) {
    if (skipped_[static_cast<size_t>(k)]) continue;
    const glm::ivec2 origin = tile_origin(k);
    if (probe_) {
      gl::api.BindFramebuffer(GL_FRAMEBUFFER, output_fbo_.id());
      gl::api.Enable(GL_SCISSOR_TEST);
      gl::api.Scissor(origin.x, origin.y, view_size_.x, view_size_.y);
      const float level = static_cast<float>(k) / 255.0f;
      const float flat[4] = {level, level, level, 1.0f};
      gl::api.ClearBufferfv(GL_COLOR, 0, flat);
      gl::api.Disable(GL_SCISSOR_TEST);
      continue;
    }
    const PassContext context{programs_, frame.scene, targets_, views_[static_cast<size_t>(k)], nullptr, frame.gl_error};
    render_view(context, PresentTarget{output_fbo_.id(), origin.x, origin.y, false}, fade);
    if (after_view_) after_view_(k, views_[static_cast<size_t>(k)], targets_);
  }
  if (quilt()) {
    const lightfield::Calibration& c = display_.quilt.calibration;
    const lightfield::Interleave interleave = lightfield::interleave_of(c, views());
    gl::api.BindFramebuffer(GL_FRAMEBUFFER, native_fbo_.id());
    gl::api.Viewport(0, 0, c.screen_width, c.screen_height);
    gl::api.Disable(GL_DEPTH_TEST);
    gl::api.UseProgram(programs_.interleave->id());
    gl::api.Uniform4f(programs_.interleave_constants, static_cast<float>(interleave.pitch), static_cast<float>(interleave.tilt),
                      static_cast<float>(interleave.subpixel), static_cast<float>(interleave.center));
    gl::api.Uniform4i(programs_.interleave_panel, c.screen_width, c.screen_height, c.inverted_views ? 1 : 0, c.flip_y ? 1 : 0);
    gl::api.Uniform4i(programs_.interleave_layout, grid_.x, grid_.y, view_size_.x, view_size_.y);
    detail::bind_texture(0, output_texture_);
    gl::api.BindVertexArray(programs_.empty_vertex_array.id());
    gl::api.DrawArrays(GL_TRIANGLES, 0, 3);
    gl::api.BindVertexArray(0);
  }
  gl::api.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

void LightFieldOutput::present(const OutputFrame&, const PresentTarget& target, int width, int height) {
  const Programs& programs = programs_;
  const glm::ivec2 source = quilt() ? native_size() : output_size_;
  // Fit inside, keeping the aspect; the rest is black. A quilt's panel image is meant pixel for pixel,
  // and is, when the surface is the panel.
  const double scale = std::min(static_cast<double>(width) / source.x, static_cast<double>(height) / source.y);
  const int w = std::max(1, static_cast<int>(source.x * scale)), h = std::max(1, static_cast<int>(source.y * scale));
  const int x = target.x + (width - w) / 2, y = target.y + (height - h) / 2;
  gl::api.BindFramebuffer(GL_DRAW_FRAMEBUFFER, target.framebuffer);
  gl::api.Viewport(target.x, target.y, width, height);
  const float black[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  gl::api.ClearBufferfv(GL_COLOR, 0, black);
  if (target.srgb) {
    // The outputs hold sRGB-encoded bytes; a blit into an sRGB framebuffer would encode them again.
    gl::api.Viewport(x, y, w, h);
    gl::api.Disable(GL_DEPTH_TEST);
    gl::api.UseProgram(programs.decode_copy->id());
    gl::api.Uniform4i(programs.decode_copy_rect, x, y, w, h);
    detail::bind_texture(0, quilt() ? native_texture_ : output_texture_);
    gl::api.BindVertexArray(programs.empty_vertex_array.id());
    gl::api.DrawArrays(GL_TRIANGLES, 0, 3);
    gl::api.BindVertexArray(0);
  } else {
    gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, quilt() ? native_fbo_.id() : output_fbo_.id());
    gl::api.BlitFramebuffer(0, 0, source.x, source.y, x, y, x + w, y + h, GL_COLOR_BUFFER_BIT,
                            w == source.x ? GL_NEAREST : GL_LINEAR);
    gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  }
  gl::api.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
}

std::vector<uint8_t> LightFieldOutput::read_output() const {
  return read_presented(PresentTarget{output_fbo_.id(), 0, 0, false}, output_size_.x, output_size_.y);
}

std::vector<uint8_t> LightFieldOutput::read_view(int k) const {
  const glm::ivec2 origin = tile_origin(k);
  return read_presented(PresentTarget{output_fbo_.id(), origin.x, origin.y, false}, view_size_.x, view_size_.y);
}

std::vector<uint8_t> LightFieldOutput::read_native() const {
  const glm::ivec2 size = native_size();
  return read_presented(PresentTarget{native_fbo_.id(), 0, 0, false}, size.x, size.y);
}

bool LightFieldRenderer::init(gl::Session& session, std::string& error) {
  caps_ = session.caps();
  return programs_.build(session, error);
}

bool LightFieldRenderer::upload(const scene::Scene& scene, std::string&) {
  source_ = std::make_shared<const scene::Scene>(scene);
  uploaded_ = false;
  return true;
}

bool LightFieldRenderer::configure(const lightfield::Display& display, const FrameSettings& settings, const scene::Camera& camera,
                                   std::string& error) {
  if (source_ == nullptr) {
    error = "no scene uploaded";
    return false;
  }
  if (!uploaded_ || !same_geometry(display, uploaded_for_)) {
    const scene::Scene prepared = prepare_for_display(*source_, display, subdivision_);
    if (!scene_.upload(prepared, caps_, error)) return false;
    uploaded_ = true;
    uploaded_for_ = display;
  }
  gl_error_.clear();
  output_.show_on(display);
  if (!output_.configure(settings, scene_, false, error)) return false;
  output_.aim(camera);
  return true;
}

void LightFieldRenderer::render() {
  output_.render(OutputFrame{scene_, 1.0f, nullptr, &gl_error_});
}

}  // namespace render
