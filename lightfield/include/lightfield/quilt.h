#pragma once
// Looking Glass style light field displays: a quilt of N views (columns x rows, view 0 at the bottom
// left), rendered by off-axis cameras on a horizontal line across the view cone, and the lenticular
// interleave that turns the quilt into the panel's native image, derived from the vendor's
// calibration (visual.json) as the formula states it.
//
// Pure math, no GL.
#include <glm/glm.hpp>

namespace lightfield {

// The fields of visual.json that the interleave uses. The file must give all but the flags and the
// view cone; a field it omits keeps the value here (parse_calibration).
struct Calibration {
  double pitch{}, slope{}, center{}, dpi{};
  int screen_width{}, screen_height{};
  bool inverted_views = false;  // invView
  bool flip_x = false, flip_y = false;
  double view_cone_deg = 40.0;
};

// Every field is the display file's (display_file.h); zero until it is read.
struct QuiltDisplay {
  Calibration calibration;
  int columns{}, rows{};
  int view_width{}, view_height{};
  int views() const { return columns * rows; }
};

// The interleave's constants for one calibration (interleave_of).
struct Interleave {
  double pitch{};     // p = pitch * screenW / DPI * cos(atan(1 / slope))
  double tilt{};      // t = screenH / (screenW * slope), negated when flipImageX
  double subpixel{};  // s = 1 / (3 * screenW)
  double center{};
  bool inverted_views = false;
  int views{};
};
Interleave interleave_of(const Calibration& calibration, int views);

// The fraction z in [0, 1) that selects the view for colour channel `channel` (0 red, 1 green, 2 blue)
// of the panel pixel at column x and row y counted from the bottom.
double view_fraction(const Interleave& interleave, const Calibration& calibration, int x, int y, int channel);
// The view that subpixel shows: floor(z * N), z from view_fraction.
int view_of_subpixel(const Interleave& interleave, const Calibration& calibration, int x, int y, int channel);

// View k's tile: column and row counted from the bottom left.
glm::ivec2 tile_of(const QuiltDisplay& quilt, int view);

// View k of N: the central camera (eye, looking at target with `up`, vertical field of view fov_y,
// aspect width / height) moved sideways along its right vector to the angle
// (k / (N - 1) - 1/2) * view cone seen from the target, looking the same way, its frustum sheared
// so that the plane through the target shows the same window in every view.
struct OffAxisView {
  glm::dmat4 view{1.0}, projection{1.0};
  glm::dvec3 eye{0.0};
};
OffAxisView quilt_view(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up, double fov_y, double aspect,
                       double near, double far, double view_cone_deg, int view, int views);

}  // namespace lightfield
