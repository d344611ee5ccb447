#pragma once
// HoloVizio-style light field displays (Doronin et al., section 3): a row of optical modules behind a
// screen that lets their light through unchanged horizontally and diffuses it vertically, seen from an
// observer line. Three spaces: world (the scene); physical (x along the observer line, y up, z towards
// the observer, the screen at z = 0, the observer line at y = y_obs, z = D); and per module, image (its
// texture's pixels, with z the physical z). World to physical is affine; physical to image is not (a
// horizontal perspective from the module, a vertical one from the observer line), which is why the
// renderer keeps world positions per pixel and runs Algorithm 2.
//
// Pure math, no GL. Functions that can fail return an empty optional or false.
#include <glm/glm.hpp>

#include <optional>
#include <vector>

namespace lightfield {

struct Box {
  glm::dvec3 min{}, max{};
};

// Every field is the display file's (display_file.h), or the default it documents where the file may
// omit it; zero until it is read.
struct ModulesDisplay {
  double screen_width{}, screen_height{};  // the screen spans [-w/2, w/2] x [-h/2, h/2] at z = 0
  double observer_distance{};              // D
  double observer_height{};                // y_obs
  std::vector<double> module_x;            // physical x of each module, in order
  double module_z{};                       // the modules' plane, behind the screen (< 0)
  int width{}, height{};                   // each module's image in pixels
  glm::dvec2 footprint{};                  // the screen x range each module's image spans
  std::optional<Box> world_roi;            // empty: the scene's bounds
  Box physical_roi;                        // where the world box goes, around the screen
};

// World to physical: the world box scaled uniformly to fit inside the physical box, centred in it.
// No rotation: world +z faces the observers, as glTF's front does.
struct RoiTransform {
  double scale = 1.0;      // physical units per world unit
  glm::dvec3 offset{0.0};  // physical = world * scale + offset
  glm::dvec3 to_physical(const glm::dvec3& world) const { return world * scale + offset; }
  glm::dvec3 to_world(const glm::dvec3& physical) const { return (physical - offset) / scale; }
  glm::dmat4 world_to_physical() const;
  glm::dmat4 physical_to_world() const;
};
// Empty when either box is not positive along every axis.
std::optional<RoiTransform> roi_transform(const Box& world, const Box& physical);
// The world box a display maps: its own roi.world_min/max, or the scene's bounds, given a thousandth
// of their largest side along any axis where they are flat (a single quad still maps to a box).
Box world_roi(const ModulesDisplay& display, const Box& scene_bounds);

// One module as the shaders see it, in physical units (module_of).
struct Module {
  double x{}, z{};  // its centre of projection P (horizontally)
  double observer_distance{}, observer_height{}, screen_height{};
  double footprint0{}, footprint1{};
  int width{}, height{};
  // The physical z range it rasterises: the ROI's depth widened by that depth on each side, kept
  // strictly between the module's plane and the observer line, where the mapping is defined.
  double z_front{}, z_back{};
};
Module module_of(const ModulesDisplay& display, int k);

// Where on the screen module `m` shows the physical point q: the pixel whose ray meets the screen at
// S, S.x = P.x + (q.x - P.x) * (-P.z) / (q.z - P.z), S.y = y_obs + (q.y - y_obs) * D / (D - q.z).
glm::dvec2 screen_point(const Module& m, const glm::dvec3& q);
// Physical point -> image: (u, v, z) with u to the right and v down from the top row, in pixels (the
// centre of pixel (i, j) at (i + 0.5, j + 0.5)), z = q.z. Empty where q is not strictly between the
// module's plane and the observer line.
std::optional<glm::dvec3> physical_to_image(const Module& m, const glm::dvec3& q);
// The screen point of image position (u, v), and the point of the observer line whose view ray
// passes through it: x = S.x - (S.x - P.x) * D / P.z.
glm::dvec3 screen_point_of_pixel(const Module& m, double u, double v);
glm::dvec3 observer_point(const Module& m, const glm::dvec3& screen);

// The clip-space position the G-buffer's vertex stage gives q (gles_shaders/lightfield.glsl computes
// the same): w = (q.z - P.z) / -P.z makes the horizontal perspective exact for the rasteriser; the
// vertical one is per vertex only.
glm::dvec4 clip_position(const Module& m, const glm::dvec3& q);
// How far (in pixels) the rasteriser draws points of the straight physical edge a-b from where the
// module really shows them: attributes interpolate linearly in clip space, so the edge's point at t
// lands at the clip position interpolated at t. The maximum over the edge (sampled finely).
double edge_error_pixels(const Module& m, const glm::dvec3& a, const glm::dvec3& b);

// Whether any point of the physical box (clipped to the module's depth range) lands in the module's
// image: the image of a box is bounded by the images of its corners, as S.x depends on x and z only
// and S.y on y and z only, each a perspective.
bool sees(const Module& m, const Box& physical_box);

// Tiles of a montage of `count` images (at least one; a display file has 1..1024 modules): columns x
// rows, as square as it gets.
glm::ivec2 montage_grid(int count);

}  // namespace lightfield
