#include "render/uniform_blocks.h"

#include <algorithm>
#include <cmath>

namespace render {
namespace {

// How far a history texel's depth may differ from the reprojected point's, relative to that depth,
// and how far its normal may turn, before it counts as another surface (a disocclusion). The depth
// tolerance covers a slanted face's change across the bilinear footprint; the normal test catches
// what depth cannot tell apart, such as a crease.
constexpr float kHistoryDepthTolerance = 0.03f;
constexpr float kHistoryNormalCosine = 0.9f;

// The key light's direction in view space: from the upper left, in front, as a photographer's.
const glm::vec3 kLightDirection = glm::normalize(glm::vec3(-0.4f, 0.6f, 0.7f));

}  // namespace

shared_layout::TemporalParams pack_temporal_params(const ViewTargets& targets, const View& view, bool moved) {
  const FrameSettings& settings = targets.settings();
  const glm::dmat4 view_to_world = glm::inverse(view.view);
  shared_layout::TemporalParams params{};
  params.current_to_previous = glm::mat4(targets.ao_view * view_to_world);
  params.previous_projection = glm::mat4(targets.ao_projection);
  params.view_to_world = glm::mat4(view_to_world);
  params.unproject = targets.ssao_params.unproject;
  params.far_plane = static_cast<float>(view.far);
  params.previous_far = static_cast<float>(targets.ao_far);
  params.depth_tolerance = kHistoryDepthTolerance;
  params.normal_cosine = kHistoryNormalCosine;
  params.has_history = targets.have_ao ? 1 : 0;
  params.max_frames = settings.history;
  params.ao_shift = targets.ssao_params.ao_shift;
  params.moved = moved ? 1 : 0;
  params.ao_width = targets.ao_width();
  params.ao_height = targets.ao_height();
  params.full_width = settings.width;
  params.full_height = settings.height;
  return params;
}

shared_layout::CompositeParams pack_composite_params(const ViewTargets& targets, const View& view, glm::ivec2 viewport,
                                                     float fade, const SceneGpu& scene) {
  const FrameSettings& settings = targets.settings();
  const EnvironmentGpu& environment = scene.environment();
  shared_layout::CompositeParams params{};
  params.light_direction = glm::vec4(kLightDirection, 0.0f);
  // A scene that brings its own lights was lit by its author: the player's light would add to it.
  params.light_color = glm::vec4(glm::vec3(scene.light_count() > 0 ? 0.0f : settings.key_light), 0.0f);
  params.view_to_world = glm::mat4(glm::inverse(view.view));
  for (size_t i = 0; i < environment.irradiance.size(); ++i) params.irradiance[i] = environment.irradiance[i];
  params.specular_max_level = static_cast<float>(std::max(environment.levels - 1, 0));
  params.environment_intensity = settings.environment_intensity;
  // A module's pixels are seen from wherever its ray meets the observer line; straight ahead is
  // what a horizontal-parallax display's viewer sees on average, and stays the same from module to
  // module, so highlights do not flicker across the views.
  params.viewer_straight_ahead = view.module.has_value() ? 1 : 0;
  params.background = glm::vec4(settings.background, 1.0f);
  // From this view's projection, not the SSAO block's: that one is only refreshed when AO runs,
  // and the shading's view vector needs it every frame.
  const glm::mat4 projection(view.projection);
  params.unproject = glm::vec4(1.0f / projection[0][0], 1.0f / projection[1][1], projection[2][0], projection[2][1]);
  params.apply_ao = settings.ao ? 1 : 0;
  params.ao_shift = settings.ao_settings.half_resolution ? 1 : 0;
  params.viewport_x = viewport.x;
  params.viewport_y = viewport.y;
  params.full_width = settings.width;
  params.full_height = settings.height;
  params.ao_width = targets.ao_width();
  params.ao_height = targets.ao_height();
  params.near_plane = static_cast<float>(view.near);
  params.far_plane = static_cast<float>(view.far);
  params.inverse_far = inverse_far(view);
  params.fade = fade;
  params.ao_strength = settings.ao_strength;
  params.plane_tolerance = targets.upsample_plane_tolerance();
  return params;
}

shared_layout::LightParams pack_light_params(const std::vector<scene::Light>& lights) {
  static_assert(MAX_LIGHTS == scene::kMaxLights);
  shared_layout::LightParams params{};
  for (const scene::Light& light : lights) {
    if (params.count == MAX_LIGHTS) break;
    const size_t i = static_cast<size_t>(params.count++);
    const bool positioned = light.type != scene::Light::Type::directional;
    params.color[i] = glm::vec4(light.color, positioned ? 1.0f : 0.0f);
    const glm::dvec3 position = positioned ? light.position : -light.direction;
    params.position[i] =
        glm::vec4(glm::vec3(position), light.range > 0.0 ? static_cast<float>(1.0 / (light.range * light.range)) : 0.0f);
    params.axis[i] = glm::vec4(glm::vec3(light.direction), 0.0f);
    if (light.type == scene::Light::Type::spot) {
      // glTF's spot falloff (KHR_lights_punctual, "Inner and Outer Cone Angles"); the cone's cosines
      // differ by at least the loader's inner < outer, floored so the scale stays finite.
      const double cos_outer = std::cos(light.outer_cone);
      const double scale = 1.0 / std::max(0.001, std::cos(light.inner_cone) - cos_outer);
      params.cone[i] = glm::vec4(static_cast<float>(scale), static_cast<float>(-cos_outer * scale), 0.0f, 0.0f);
    } else {
      params.cone[i] = glm::vec4(0.0f, 1.0f, 0.0f, 0.0f);
    }
  }
  return params;
}

shared_layout::UpsampleParams pack_upsample_params(const ViewTargets& targets) {
  shared_layout::UpsampleParams params{};
  params.full_width = targets.settings().width;
  params.full_height = targets.settings().height;
  params.ao_width = targets.ao_width();
  params.ao_height = targets.ao_height();
  // Depths are compared as depth / far: the same 1/far the present pass scaled them with.
  params.inverse_far = targets.last_inverse_far;
  params.plane_tolerance = targets.upsample_plane_tolerance();
  params.unproject = targets.ssao_params.unproject;
  return params;
}

shared_layout::ModuleParams pack_module_params(const ModuleView& view) {
  const lightfield::Module& m = view.module;
  shared_layout::ModuleParams params{};
  params.world_to_physical = glm::mat4(view.roi.world_to_physical());
  params.physical_to_world = glm::mat4(view.roi.physical_to_world());
  params.module_x = static_cast<float>(m.x);
  params.module_z = static_cast<float>(m.z);
  params.observer_distance = static_cast<float>(m.observer_distance);
  params.observer_height = static_cast<float>(m.observer_height);
  params.footprint_x0 = static_cast<float>(m.footprint0);
  params.footprint_x1 = static_cast<float>(m.footprint1);
  params.screen_height = static_cast<float>(m.screen_height);
  params.physical_per_world = static_cast<float>(view.roi.scale);
  params.z_front = static_cast<float>(m.z_front);
  params.z_back = static_cast<float>(m.z_back);
  params.seed_cell = static_cast<float>(view.seed_cell);
  params.width = m.width;
  params.height = m.height;
  params.pixel_turns = view.pixel_turns ? 1 : 0;
  return params;
}

}  // namespace render
