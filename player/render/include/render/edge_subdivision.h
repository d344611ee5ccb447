#pragma once
// Light field modules place vertices by a non-linear world-to-image transform, and the rasteriser
// joins them with straight lines: a long edge that changes depth is drawn up to many pixels from
// where the module shows its points (lightfield::edge_error_pixels). This splits such edges until
// every edge's error is below a bound, for every module of a display. Pure CPU.
#include "lightfield/modules.h"
#include "scene/scene.h"

namespace render {

struct SubdivisionReport {
  double worst_before_px = 0.0, worst_after_px = 0.0;  // largest edge error over the modules checked
  size_t triangles_before = 0, triangles_after = 0;
  int passes = 0;
  bool capped = false;  // stopped at the triangle budget before reaching the bound
};

// Splits, in passes, every edge whose error exceeds `max_error_px` in any of the display's modules
// (all of them up to 16, else 16 spread over the row, the two ends included) at its midpoint, and
// re-triangulates each triangle by the number of its split edges, so neighbours stay joined (no
// T-junctions). Normals and texture coordinates are interpolated. Stops after `max_passes` passes or
// when the scene would exceed `max_triangles`.
scene::Scene subdivide_for_modules(const scene::Scene& scene, const lightfield::ModulesDisplay& display,
                                   const lightfield::RoiTransform& roi, double max_error_px, SubdivisionReport& report,
                                   int max_passes = 8, size_t max_triangles = 4'000'000);

}  // namespace render
