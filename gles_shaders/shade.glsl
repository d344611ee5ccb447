// A surface point's light (pbr.glsl's BRDF): the environment (SH irradiance, the prefiltered cube
// map, the split-sum table), its diffuse part scaled by `visibility` and its specular part by the
// specular occlusion derived from it, plus the key light, or the scene's own lights in its place,
// which visibility does not touch: they stand for lights with shadows of their own that
// screen-space AO does not know. Shared by the present pass (opaque surfaces from the G-buffer)
// and the forward pass (blended ones). NO_SCENE_LIGHTS: the present pass of a scene without lights
// of its own leaves their loop out (llvmpipe paid for it even at a count of 0).
#ifndef SHADE_GLSL
#define SHADE_GLSL

#include "shared_layout.glsl"
#include "pbr.glsl"

layout(std140, binding = BINDING_COMPOSITE_PARAMS) uniform CompositeBlock { CompositeParams composite; };
layout(std140, binding = BINDING_LIGHT_PARAMS) uniform LightBlock { LightParams lights; };
uniform highp samplerCube u_specular;  // the environment prefiltered per roughness, a level each
uniform highp sampler2D u_brdf_lut;    // the split-sum table: (A, B) at (n.v, roughness)

highp vec3 linear_to_srgb(highp vec3 c) {
  c = clamp(c, 0.0, 1.0);
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

// `normal` and `view_position` in view space.
highp vec3 shade(highp vec3 base_color, highp float metallic, highp float roughness, highp vec3 normal,
                 highp vec3 view_position, highp float visibility) {
  highp vec3 to_viewer = composite.viewer_straight_ahead != 0 ? vec3(0.0, 0.0, 1.0) : -normalize(view_position);
  SurfacePoint s = surface_point(base_color, metallic, roughness, normal, to_viewer);
  // Normalised in world space: a light field's view space is physical space, scaled from the world.
  highp mat3 to_world = mat3(composite.view_to_world);
  highp vec3 irradiance = sh_irradiance(composite.irradiance, normalize(to_world * normal)) * composite.environment_intensity;
  highp vec3 prefiltered =
      textureLod(u_specular, to_world * reflect(-s.v, normal), s.roughness * composite.specular_max_level).rgb *
      composite.environment_intensity;
  highp vec3 environment_diffuse, environment_specular;
  environment_light(s, texture(u_brdf_lut, vec2(s.nv, s.roughness)).rg, irradiance, prefiltered, environment_diffuse,
                    environment_specular);
  highp vec3 color = environment_diffuse * visibility + environment_specular * specular_occlusion(s.nv, visibility, s.roughness);
  color += punctual_light(s, composite.light_direction.xyz, composite.light_color.rgb);
#ifndef NO_SCENE_LIGHTS
  if (lights.count > 0) {
    highp vec3 world_position = (composite.view_to_world * vec4(view_position, 1.0)).xyz;
    // World to view for directions: the view's rotation and a uniform scale (a module's), which
    // the normalisation removes.
    highp mat3 to_view = transpose(to_world);
    for (int i = 0; i < lights.count; ++i) {
      highp vec4 position = lights.position[i];
      highp vec3 to_light = position.xyz;
      highp float falloff = 1.0;
      if (lights.color[i].a > 0.0) {
        to_light -= world_position;
        highp float distance_squared = max(dot(to_light, to_light), 1e-8);
        to_light *= inversesqrt(distance_squared);
        // KHR_lights_punctual's range window: inverse square, brought smoothly to 0 at the range.
        highp float window = clamp(1.0 - distance_squared * distance_squared * position.w * position.w, 0.0, 1.0);
        highp float cone = clamp(dot(lights.axis[i].xyz, -to_light) * lights.cone[i].x + lights.cone[i].y, 0.0, 1.0);
        falloff = window / distance_squared * cone * cone;
      }
      color += punctual_light(s, normalize(to_view * to_light), lights.color[i].rgb * falloff);
    }
  }
#endif
  return color;
}

#endif
