#pragma once
// Read-backs for output, dumps and tests: they wait for the GPU, so never in the frame loop.
// Rows come bottom-up (GL order) except where a function says otherwise.
#include "render/passes.h"
#include "render/programs.h"
#include "render/view.h"
#include "render/view_targets.h"

#include <cstdint>
#include <vector>

namespace render {

// The presented image, RGBA8, row 0 at the top.
std::vector<uint8_t> read_presented(const PresentTarget& target, int width, int height);
std::vector<float> read_linear_depth(const ViewTargets& targets);
// The G-buffer's view-space normals (gbuffer_normals.glsl): the shading normal, and the geometric
// normal of the face each pixel lies on (what the horizon estimator bounds its horizons with).
std::vector<glm::vec3> read_view_normals(const ViewTargets& targets);
std::vector<glm::vec3> read_view_face_normals(const ViewTargets& targets);
// Each pixel's motion since the previous pose in view space (ViewTargets::motion); empty without
// a motion target.
std::vector<glm::vec3> read_motion(const ViewTargets& targets);
// r: AO, g: depth / far, at the AO resolution.
std::vector<glm::vec2> read_ao(const gl::Texture& texture, int width, int height);
// Per AO texel, how many frames the temporal average holds (0 on background); empty without temporal.
std::vector<float> read_history_frames(const ViewTargets& targets);
// The AO the present pass shaded with, at full resolution: upsampled exactly as the present pass
// does it (the same GLSL function) when AO runs at half resolution.
std::vector<glm::vec2> read_ao_full(const Programs& programs, const ViewTargets& targets);

// The visible surface in world space, rows bottom-up: positions and normals with alpha 1 on objects
// and 0 on background, and linear depth. Rebuilt from the G-buffer exactly as ssao.comp rebuilds it,
// in double, so references are computed at the points SSAO saw.
struct WorldSurface {
  int width = 0, height = 0;
  std::vector<float> position, normal;  // 4 channels each
  std::vector<float> depth;             // 1 channel
};
WorldSurface read_world_surface(const ViewTargets& targets, const View& view);
// Light field modules: the same from the G-buffer's positions texture (what Algorithm 2 read), with
// depth the distance from the observer line in physical units.
WorldSurface read_module_surface(const ViewTargets& targets);

}  // namespace render
