// The world-to-image transform of one optical module (lightfield/modules.h has the same in C++ and
// the derivation): horizontally a perspective from the module at (P.x, P.z), vertically one from the
// observer line at (y_obs, D). Not a 4x4 matrix, so it runs per vertex in the G-buffer and per sample
// in Algorithm 2.
#ifndef LIGHTFIELD_GLSL
#define LIGHTFIELD_GLSL
#include "shared_layout.glsl"

layout(std140, binding = BINDING_MODULE_PARAMS) uniform ModuleBlock { ModuleParams lightfield_module; };

// The screen point S where the module shows physical point q.
highp vec2 module_screen_point(highp vec3 q) {
  highp float px = lightfield_module.module_x, pz = lightfield_module.module_z;
  highp float d = lightfield_module.observer_distance, y_obs = lightfield_module.observer_height;
  return vec2(px + (q.x - px) * (-pz) / (q.z - pz), y_obs + (q.y - y_obs) * d / max(d - q.z, 1e-6 * d));
}

// Normalised device coordinates of S in the module's image (x right, y up, both -1..1).
highp vec2 module_ndc(highp vec2 s) {
  highp float x0 = lightfield_module.footprint_x0, x1 = lightfield_module.footprint_x1;
  return vec2((s.x - x0) / (x1 - x0) * 2.0 - 1.0, s.y / lightfield_module.screen_height * 2.0);
}

// Clip position for the rasteriser: w = (q.z - P.z) / -P.z makes its perspective the module's
// horizontal one; depth runs from z_front (-1) to z_back (+1).
highp vec4 module_clip(highp vec3 q) {
  highp float pz = lightfield_module.module_z;
  highp float w = (q.z - pz) / -pz;
  highp float ndc_z = (lightfield_module.z_front - q.z) / (lightfield_module.z_front - lightfield_module.z_back) * 2.0 - 1.0;
  return vec4(vec3(module_ndc(module_screen_point(q)), ndc_z) * w, w);
}

// How far q lies from the observer line along z: the module's linear depth (positive; 0 marks
// background in the depth texture).
highp float module_depth(highp vec3 q) { return lightfield_module.observer_distance - q.z; }

#endif
