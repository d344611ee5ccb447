// The GPU pipeline against the CPU reference and against values known in closed form, on both
// headless platforms.
#include "harness.h"
#include "scene/procedural.h"
#include "ssao/reference.h"

#include <algorithm>
#include <iostream>
#include <optional>

namespace {

using test::Harness;

constexpr int kSide = 64;

render::FrameSettings small_settings() {
  render::FrameSettings settings;
  settings.width = settings.height = kSide;
  settings.check_errors = true;
  // These tests read the AO pixel for pixel against the G-buffer; half resolution has its own cases.
  settings.ao_settings.half_resolution = false;
  return settings;
}

class Pipeline : public ::testing::TestWithParam<std::string> {};

struct Comparison {
  float max_difference = 0.0f;
  size_t off_by_more = 0;  // pixels differing by more than `tolerance`
};

Comparison compare(const std::vector<glm::vec2>& gpu, const std::vector<glm::vec2>& cpu, float tolerance) {
  Comparison result;
  for (size_t i = 0; i < gpu.size(); ++i) {
    const float difference = std::abs(gpu[i].x - cpu[i].x);
    result.max_difference = std::max(result.max_difference, difference);
    if (difference > tolerance) ++result.off_by_more;
  }
  return result;
}

// The GPU's result against the CPU reference fed the GPU's own G-buffer (depth and normals), so both
// see the very same per-pixel inputs.
// Point-sampled estimators (sphere, hemisphere): the two evaluate the same float expressions in
// possibly different order, so a sample lying within rounding of a depth or texel boundary may flip:
// that moves one pixel's AO by one sample's weight (1/samples). Allowed at up to 1% of pixels; all
// others agree to half-float precision.
// Horizon: its AO is continuous in the tap depths (a tap's elevation fades to nothing at the end of
// its reach), and the only discontinuity, a tap's texel, floor(offset + 0.5), needs a tap within
// float rounding of a texel's edge, which none of these scenes has: measured on llvmpipe (egl and
// osmesa, full and half resolution, flat and chained depth), every pixel agrees to one half-float
// step (2^-11 = 0.00049 at AO in [0.5, 1), where both round to rgba16f) and the rest, llvmpipe's
// sin/cos/acos against libm's, stays under 1e-4.
// So every horizon pixel must agree to 1e-3: a sign flipped or a tap off by one anywhere in the
// estimator moves far more than that.
void expect_gpu_equals_reference(const Harness& h, const std::string& what, bool mediump_reference = false) {
  const render::FrameSettings& settings = h.renderer.settings();
  const ssao::Estimator estimator = settings.ao_settings.estimator;
  const auto depth = h.renderer.read_linear_depth();
  const auto chain = ssao::build_depth_chain(depth, settings.width, settings.height);
  const auto cpu_raw = ssao::reference_ssao(chain, h.renderer.read_view_normals(), h.renderer.read_view_face_normals(),
                                            h.renderer.ssao_params(), h.renderer.inverse_far(), estimator, mediump_reference);
  const auto gpu_raw = h.renderer.read_ao_raw();
  ASSERT_EQ(gpu_raw.size(), cpu_raw.size());
  if (estimator == ssao::Estimator::horizon) {
    const Comparison raw = compare(gpu_raw, cpu_raw, 1e-3f);
    EXPECT_EQ(raw.off_by_more, 0u) << what << ", max difference " << raw.max_difference;
  } else {
    const float flip = 1.0f / static_cast<float>(settings.ao_settings.samples) + 1e-3f;
    const Comparison raw = compare(gpu_raw, cpu_raw, 2e-3f);
    EXPECT_LE(raw.max_difference, flip) << what;
    EXPECT_LE(raw.off_by_more, gpu_raw.size() / 100) << what;
  }
  auto low = gpu_raw;
  if (settings.blur.mode != ssao::Blur::off) {
    // The blur, fed the GPU's own raw AO, must match to within half-float rounding of the sums.
    const auto normals = h.renderer.read_view_normals();
    const auto cpu_h = ssao::reference_blur(gpu_raw, h.renderer.blur_params(0), settings.blur.mode, normals, settings.width);
    low = ssao::reference_blur(cpu_h, h.renderer.blur_params(1), settings.blur.mode, normals, settings.width);
    const Comparison blurred = compare(h.renderer.read_ao_blurred(), low, 2e-3f);
    EXPECT_EQ(blurred.off_by_more, 0u) << what << ", max difference " << blurred.max_difference;
    low = h.renderer.read_ao_blurred();
  }
  if (settings.ao_settings.half_resolution) {
    // An interpolated AO is rounded to half float on the GPU's own terms (llvmpipe does not round to
    // nearest everywhere): one half-float step below 1, 2^-11, and no more.
    const Comparison upsampled =
        compare(h.renderer.read_ao_final(),
                ssao::reference_upsample(low, depth, h.renderer.upsample_params(), h.renderer.read_view_normals()), 4.9e-4f);
    EXPECT_EQ(upsampled.off_by_more, 0u) << what << ", max difference " << upsampled.max_difference;
  }
  EXPECT_EQ(h.renderer.gl_error(), "") << what;
}

TEST_P(Pipeline, GpuSsaoAndBlurEqualTheCpuReference) {
  for (const char* scene : {"builtin:demo", "builtin:spheres"}) {
    for (ssao::Pattern pattern : ssao::kPatterns) {
      for (ssao::Blur blur : {ssao::Blur::gaussian, ssao::Blur::bilateral, ssao::Blur::denoise}) {
        render::FrameSettings settings = small_settings();
        settings.ao_settings.pattern = pattern;
        settings.blur.mode = blur;
        Harness h;
        ASSERT_TRUE(h.start(GetParam(), scene, settings));
        expect_gpu_equals_reference(
            h, std::string(scene) + " " + std::string(ssao::name(pattern)) + " " + std::string(ssao::name(blur)));
      }
    }
  }
}

// builtin:corner at 128x128, unblurred, seen from above the corner so that both walls and the floor
// fill the view.
render::FrameSettings corner_settings(float radius) {
  render::FrameSettings settings = small_settings();
  settings.width = settings.height = 128;
  settings.radius = radius;
  settings.blur.mode = ssao::Blur::off;
  return settings;
}

scene::Framing corner_view() {
  scene::Framing view;
  view.azimuth_deg = 45.0;
  view.elevation_deg = 35.0;
  return view;
}

// The scenes above are small enough in pixels that the horizon's steps are a few pixels long; here
// the radius spans dozens, so every tap, the first one included, lands where the pixel's jitter
// puts it along its step, and the GPU must put it where the CPU reference does.
TEST_P(Pipeline, HorizonWithAWideRadiusEqualsTheCpuReference) {
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), "builtin:corner", corner_settings(1.25f), corner_view()));
  const auto depth = h.renderer.read_linear_depth();
  const float centre_depth = depth[static_cast<size_t>(64 * 128 + 64)];
  ASSERT_GT(centre_depth, 0.0f);
  const auto& params = h.renderer.ssao_params();
  const float radius_pixels = params.radii[params.first_radius].x * params.pixels_per_unit / centre_depth;
  const float half_step = 0.5f * radius_pixels / static_cast<float>(params.horizon_steps - 1);
  ASSERT_GT(half_step, 3.0f) << "the first tap's range, from 1.6 pixels to half a step, must be wide";
  expect_gpu_equals_reference(h, "corner, a radius of " + std::to_string(radius_pixels) + " pixels");
}

// --precision mediump runs the AO_MEDIUMP variant; llvmpipe computes its mediump at 32 bits, so it
// must give what highp gives, within the same tolerances, against the highp CPU reference (the fp16
// error itself is bounded on the CPU: Mediump.VariantStaysWithinTheBoundOfHighp in stress_test.cpp).
TEST_P(Pipeline, EveryEstimatorPrecisionAndResolutionEqualsTheCpuReference) {
  for (ssao::Estimator estimator : ssao::kEstimators)
    for (ssao::Precision precision : ssao::kPrecisions)
      for (bool half : {false, true})
        for (bool chain : {false, true}) {
          render::FrameSettings settings = small_settings();
          settings.ao_settings.precision = precision;
          settings.width = 96;
          settings.height = 72;
          settings.ao_settings.estimator = estimator;
          settings.ao_settings.samples = 16;
          settings.ao_settings.half_resolution = half;
          settings.ao_settings.depth_chain = chain;
          settings.radius = 1.5f;  // large enough that the depth chain's coarse levels are read
          Harness h;
          ASSERT_TRUE(h.start(GetParam(), "builtin:demo", settings));
          const std::string what = std::string(ssao::name(estimator)) + " " + std::string(ssao::name(precision)) +
                                   (half ? " half" : " full") + (chain ? " chain" : " flat");
          // The program that ran is the variant the setting names (on llvmpipe its output cannot tell).
          EXPECT_EQ(h.renderer.targets().ssao_defines.find("#define AO_MEDIUMP") != std::string_view::npos,
                    precision == ssao::Precision::mediump)
              << what << ": " << h.renderer.targets().ssao_defines;
          EXPECT_EQ(h.renderer.targets().ssao_defines.find("#define ESTIMATOR " + std::to_string(static_cast<int>(estimator))) !=
                        std::string_view::npos,
                    true)
              << what;
          expect_gpu_equals_reference(h, what);
        }
}

TEST_P(Pipeline, EachEstimatorAndPrecisionIsItsOwnProgram) {
  // play compiles every variant into one Programs up front; each must stay its own program, built
  // with its own #defines, and configure must pick the one the settings name.
  render::FrameSettings settings = small_settings();
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), "builtin:demo", settings));
  std::vector<GLuint> ids;
  std::string error;
  for (ssao::Estimator estimator : ssao::kEstimators)
    for (ssao::Precision precision : ssao::kPrecisions) {
      const std::string what = std::string(ssao::name(estimator)) + " " + std::string(ssao::name(precision));
      const gl::Program* program = h.renderer.programs().ssao(estimator, precision, error);
      ASSERT_NE(program, nullptr) << what << ": " << error;
      EXPECT_EQ(std::count(ids.begin(), ids.end(), program->id()), 0) << what << " shares a program with another variant";
      ids.push_back(program->id());
      const std::string_view defines = h.renderer.programs().ssao_defines(estimator, precision);
      EXPECT_NE(defines.find("#define ESTIMATOR " + std::to_string(static_cast<int>(estimator)) + "\n"), std::string_view::npos)
          << what;
      EXPECT_EQ(defines.find("#define AO_MEDIUMP") != std::string_view::npos, precision == ssao::Precision::mediump) << what;
      render::FrameSettings variant = settings;
      variant.ao_settings.estimator = estimator;
      variant.ao_settings.precision = precision;
      ASSERT_TRUE(h.renderer.configure(variant, error)) << what << ": " << error;
      EXPECT_EQ(h.renderer.targets().ssao_program, program) << what;
      h.renderer.render(h.camera);
      EXPECT_EQ(h.renderer.gl_error(), "") << what;
    }
}

TEST_P(Pipeline, BackgroundPixelsGetNoOcclusion) {
  for (ssao::Estimator estimator : ssao::kEstimators)
    for (bool half : {false, true}) {
      render::FrameSettings settings = small_settings();
      settings.ao_settings.estimator = estimator;
      settings.ao_settings.half_resolution = half;
      settings.blur.mode = ssao::Blur::gaussian;
      Harness h;
      ASSERT_TRUE(h.start(GetParam(), "builtin:spheres", settings));
      const auto depth = h.renderer.read_linear_depth();
      const auto final_ao = h.renderer.read_ao_final();  // full resolution either way
      const auto raw = h.renderer.read_ao_raw(), blurred = h.renderer.read_ao_blurred();
      size_t background = 0;
      for (size_t i = 0; i < depth.size(); ++i) {
        if (depth[i] > 0.0f) continue;
        ++background;
        EXPECT_EQ(final_ao[i].x, 0.0f) << ssao::name(estimator) << (half ? ", half" : ", full");
        if (!half) {
          EXPECT_EQ(raw[i].x, 0.0f);
          EXPECT_EQ(blurred[i].x, 0.0f);
        }
      }
      EXPECT_GT(background, depth.size() / 10);  // the framing leaves a border of background
    }
}

TEST_P(Pipeline, PlaneFacingTheCameraGetsTheEstimatorsPlaneValue) {
  for (int samples : {8, 16, 32}) {
    render::FrameSettings settings = small_settings();
    settings.ao_settings.estimator = ssao::Estimator::sphere;
    settings.ao_settings.radii = 5;
    settings.ao_settings.samples = samples;
    settings.blur.mode = ssao::Blur::off;
    scene::Framing head_on;
    head_on.azimuth_deg = 0.0;
    head_on.elevation_deg = 0.0;
    head_on.distance = 0.5;  // the plane fills the picture
    Harness h;
    ASSERT_TRUE(h.start(GetParam(), "builtin:plane", settings, head_on));
    const auto& params = h.renderer.ssao_params();
    // On a plane facing the camera a sample is hidden exactly when it lies more than the bias behind
    // the plane; the turn about the view axis leaves that depth unchanged, so every radius agrees.
    int behind = 0;
    for (int i = 0; i < samples; ++i) behind += params.kernel[i].z < -params.depth_bias ? 1 : 0;
    const float expected = static_cast<float>(behind) / static_cast<float>(samples);
    const auto raw = h.renderer.read_ao_raw();
    const auto depth = h.renderer.read_linear_depth();
    // Away from the border, where no sample leaves the picture.
    for (int y = 12; y < kSide - 12; ++y)
      for (int x = 12; x < kSide - 12; ++x) {
        const size_t i = static_cast<size_t>(y * kSide + x);
        ASSERT_GT(depth[i], 0.0f);
        EXPECT_NEAR(raw[i].x, expected, 1e-3f) << "pixel " << x << "," << y << ", " << samples << " samples";
      }
  }
}

// builtin:corner in closed form: floor y = 0 and walls x = 0, z = 0, each the square [0, 2]^2 of its
// plane. Depth and normal at any image point come from intersecting the eye ray with the three squares,
// not from the G-buffer, and each estimator's expectation is computed here from its definition (docs/ao.md,
// "The passes and estimators") with the very kernel, turns and radius the pass used. This is independent
// of both ssao.comp and reference.cpp, so it fails an error made in both (which the GPU-vs-CPU
// comparison cannot see).
struct AnalyticCorner {
  const shared_layout::SsaoParams& p;
  glm::dmat4 view, world_from_view;
  glm::ivec2 size;
  float radius;

  glm::dvec3 ray(glm::dvec2 ndc) const {  // view space, z = -1: the depth along it is the linear depth
    return {(ndc.x + p.unproject.z) * p.unproject.x, (ndc.y + p.unproject.w) * p.unproject.y, -1.0};
  }
  glm::dvec2 ndc_of(glm::ivec2 texel) const { return (glm::dvec2(texel) + 0.5) / glm::dvec2(size) * 2.0 - 1.0; }
  // Linear depth of the first square the ray meets (0: none), and that square's view-space normal.
  double depth(glm::dvec2 ndc, glm::dvec3* normal = nullptr) const {
    const glm::dvec3 e(world_from_view * glm::dvec4(0, 0, 0, 1)), d(world_from_view * glm::dvec4(ray(ndc), 0));
    double best = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
      if (std::abs(d[axis]) < 1e-12) continue;
      const double t = -e[axis] / d[axis];
      const glm::dvec3 hit = e + t * d;
      bool inside = t > 0.0;
      for (int other = 0; other < 3; ++other)
        if (other != axis) inside = inside && hit[other] >= 0.0 && hit[other] <= 2.0;
      if (!inside || (best > 0.0 && t >= best)) continue;
      best = t;
      if (normal != nullptr) {
        glm::dvec3 n(0.0);
        n[axis] = 1.0;
        *normal = glm::normalize(glm::dmat3(view) * n);
      }
    }
    return best;
  }
  glm::dvec2 turn(glm::ivec2 pixel) const { return glm::dvec2(tile_entry(pixel)); }
  double tap_jitter(glm::ivec2 pixel) const { return tile_entry(pixel).z; }
  glm::vec4 tile_entry(glm::ivec2 pixel) const {
    return p.rotation[(pixel.y % SSAO_ROTATION_TILE) * SSAO_ROTATION_TILE + pixel.x % SSAO_ROTATION_TILE];
  }

  // Sphere and hemisphere: the share of kernel points hidden by the surface, as an interval: a point
  // whose decision lies within 1e-3 R of its threshold, or near its texel's edge, may go either way
  // (float rounding, the raster's depth against this exact one, the G-buffer's half-float normal).
  std::pair<double, double> hidden_share(glm::ivec2 pixel, ssao::Estimator estimator) const {
    glm::dvec3 n;
    const double d = depth(ndc_of(pixel), &n);
    const glm::dvec3 position = ray(ndc_of(pixel)) * d;
    const glm::dvec2 t = turn(pixel);
    glm::dmat3 basis(t.x, t.y, 0.0, -t.y, t.x, 0.0, 0.0, 0.0, 1.0);  // sphere: a turn about the view axis
    if (estimator == ssao::Estimator::hemisphere) {                  // z along the normal, x the turn's direction in the face
      glm::dvec3 tangent = glm::dvec3(t, 0.0) - n * glm::dot(glm::dvec3(t, 0.0), n);
      if (glm::dot(tangent, tangent) < 1e-6) tangent = glm::dvec3(-t.y, t.x, 0.0) - n * glm::dot(glm::dvec3(-t.y, t.x, 0.0), n);
      tangent = glm::normalize(tangent);
      basis = glm::dmat3(tangent, glm::cross(n, tangent), n);
    }
    const double r = radius, bias = p.depth_bias * r, margin = 1e-3 * r;
    // The hemisphere moves the stored depth along the shaded point's tangent plane to the sample.
    const auto plane_depth = [&](glm::dvec2 ndc) { return glm::dot(n, position) / glm::dot(n, ray(ndc)); };
    int sure = 0, unsure = 0;
    for (int i = 0; i < p.samples; ++i) {
      const glm::dvec3 offset = r * (basis * glm::dvec3(p.kernel[i]));
      const glm::dvec4 clip = glm::dmat4(p.projection) * glm::dvec4(position + offset, 1.0);
      if (clip.w <= 0.0) continue;
      const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
      // 0: not hidden, 1: hidden, 2: within rounding of a threshold.
      const auto decide = [&](glm::ivec2 texel) {
        if (texel.x < 0 || texel.y < 0 || texel.x >= size.x || texel.y >= size.y) return 0;
        double surface = depth(ndc_of(texel));
        if (surface <= 0.0) return 0;
        if (estimator == ssao::Estimator::hemisphere) surface += std::clamp(plane_depth(ndc) - plane_depth(ndc_of(texel)), -r, r);
        const double in_front = (-offset.z - bias) - (surface - d);  // > 0: the surface hides the point
        const double in_range = r - std::abs(surface - d);           // > 0: the surface is near enough
        if (std::abs(in_front) < margin || std::abs(in_range) < margin) return 2;
        return in_front > 0.0 && in_range > 0.0 ? 1 : 0;
      };
      const glm::dvec2 uv = (ndc * 0.5 + 0.5) * glm::dvec2(size);
      const glm::ivec2 texel(glm::floor(uv));
      int decision = decide(texel);
      // The G-buffer's normal is a half float (11 bits), which turns the hemisphere's kernel by up to
      // 1e-3 rad: a point within 0.02 pixels of its texel's edge may land in the neighbour.
      for (int axis = 0; axis < 2; ++axis) {
        const double fraction = uv[axis] - std::floor(uv[axis]);
        glm::ivec2 neighbour = texel;
        neighbour[axis] += fraction < 0.5 ? -1 : 1;
        if (std::min(fraction, 1.0 - fraction) < 0.02 && decide(neighbour) != decision) decision = 2;
      }
      if (decision == 2)
        ++unsure;
      else
        sure += decision;
    }
    return {static_cast<double>(sure) / p.samples, static_cast<double>(sure + unsure) / p.samples};
  }

  // Horizon (GTAO, the occluded share of the slices' open arcs), in closed form per slice from the
  // horizon angles the taps find; nullopt where a tap lies within rounding of its texel's edge and
  // the texel beyond that edge would rise differently (the pixel may go either way there).
  std::optional<double> horizon(glm::ivec2 pixel) const {
    glm::dvec3 n;
    const double d = depth(ndc_of(pixel), &n);
    const glm::dvec3 position = ray(ndc_of(pixel)) * d, view_direction = glm::normalize(-position);
    const double radius_pixels = radius * p.pixels_per_unit / d;
    if (radius_pixels < 1.0) return 0.0;
    const int steps = p.horizon_steps, slices = std::max(1, p.samples / (2 * steps));
    const double pi = std::acos(-1.0), turn_angle = std::atan2(turn(pixel).y, turn(pixel).x);
    double occluded = 0.0, open = 0.0;
    for (int slice = 0; slice < slices; ++slice) {
      const double phi = (pi * slice + 0.5 * turn_angle) / slices;  // evenly spaced slices
      const glm::dvec2 direction(std::cos(phi), std::sin(phi));
      // The slice plane holds the view direction and the screen direction; the normal projected into it
      // is at angle gamma from the view direction, towards the positive side.
      const glm::dvec3 ortho = glm::dvec3(direction, 0.0) - glm::dot(glm::dvec3(direction, 0.0), view_direction) * view_direction;
      const glm::dvec3 axis = glm::normalize(glm::cross(ortho, view_direction));
      const glm::dvec3 projected = n - axis * glm::dot(n, axis);
      const double length = glm::length(projected);
      if (length < 1e-6) continue;
      const double gamma = (glm::dot(ortho, projected) >= 0.0 ? 1.0 : -1.0) *
                           std::acos(std::clamp(glm::dot(projected, view_direction) / length, -1.0, 1.0));
      // Each side's highest elevation above the tangent plane: a tap's angle from the slice's tangent
      // on its side, its rise measured along the normal (so a tap on the face, off the slice, rises by
      // nothing), its pseudo-angle scaled down linearly from 1 to 2 radii away.
      const glm::dvec3 tangent_plus = glm::cross(projected, axis) / length;
      double elevation[2] = {0.0, 0.0};  // side 0 towards +direction (angle > 0), side 1 (< 0)
      for (int step = 0; step < steps; ++step) {
        // The rest equally spaced to the radius, each the pixel's jitter of a step beyond the end of the
        // step before (0.5: at the ends of the steps), a pixel apart at least; the first the jitter of
        // the way from 1.6 pixels out to half a step.
        const double spacing = radius_pixels / (steps - 1), jitter = tap_jitter(pixel);
        const double distance_pixels = steps == 1  ? radius_pixels
                                       : step == 0 ? std::min(1.6 + jitter * (std::max(0.5 * spacing, 1.6) - 1.6), radius_pixels)
                                                   : std::max((step + jitter - 0.5) * spacing, double(step));
        for (int side = 0; side < 2; ++side) {
          const auto tap_elevation = [&](glm::ivec2 texel) {
            if (texel.x < 0 || texel.y < 0 || texel.x >= size.x || texel.y >= size.y) return 0.0;
            const double tap_depth = depth(ndc_of(texel));
            if (tap_depth <= 0.0) return 0.0;
            const glm::dvec3 delta = ray(ndc_of(texel)) * tap_depth - position;
            const double distance = glm::length(delta);
            constexpr double kFadeEnd = 2.0;
            if (distance >= kFadeEnd * radius || distance <= 0.0) return 0.0;
            const double rise = glm::dot(delta, n) / length;
            if (rise <= 0.0) return 0.0;
            const double weight = std::min(1.0, (kFadeEnd * radius - distance) / ((kFadeEnd - 1.0) * radius));
            const double along = glm::dot(delta, tangent_plus) * (side == 0 ? 1.0 : -1.0);
            // As a pseudo-angle (0 on the tangent plane, 1 along the normal, 2 at the far tangent),
            // capped at 20 times rise / (|along| + rise), which binds only past about pi - 0.1.
            const double share = rise / (std::abs(along) + rise);
            return std::min(along >= 0.0 ? share : 2.0 - share, 20.0 * share) * weight;
          };
          // The GPU takes the texel floor(offset + 0.5); within rounding of a texel's edge it may take the
          // neighbour, which only matters where the two rise differently.
          const glm::dvec2 offset = (side == 0 ? 1.0 : -1.0) * distance_pixels * direction + 0.5;
          const glm::ivec2 texel = pixel + glm::ivec2(glm::floor(offset));
          const double angle = tap_elevation(texel);
          for (int axis_index = 0; axis_index < 2; ++axis_index) {
            const double to_edge = offset[axis_index] - std::round(offset[axis_index]);
            if (std::abs(to_edge) >= 1e-3) continue;
            glm::ivec2 neighbour = texel;
            neighbour[axis_index] += to_edge < 0.0 ? 1 : -1;
            if (std::abs(tap_elevation(neighbour) - angle) > 1e-6) return std::nullopt;
          }
          elevation[side] = std::max(elevation[side], angle);
        }
      }
      for (double& e : elevation) e = std::atan2(std::min(e, 2.0 - e), 1.0 - e);  // pseudo-angle to radians
      const double high[2] = {gamma + pi / 2 - std::min(elevation[0], std::max(gamma + pi / 2, 0.0)),
                              gamma - pi / 2 + std::min(elevation[1], std::max(pi / 2 - gamma, 0.0))};
      // Visible arc from high[1] to high[0], each clamped to the hemisphere about the projected normal,
      // weighted by cos(angle - gamma) * |sin(angle)| (the slice's cosine and area factors):
      // the integral of that from gamma to h is (cos(gamma) + 2 h sin(gamma) - cos(2 h - gamma)) / 4.
      const double h1 = std::min(high[0], gamma + pi / 2), h0 = std::max(high[1], gamma - pi / 2);
      const auto arc = [&](double h) { return (std::cos(gamma) + 2.0 * h * std::sin(gamma) - std::cos(2.0 * h - gamma)) / 4.0; };
      const double visible = arc(h1) + arc(h0), all = arc(gamma + pi / 2) + arc(gamma - pi / 2);
      occluded += length * (all - visible);
      open += length * all;
    }
    return open > 0.0 ? std::clamp(occluded / open, 0.0, 1.0) : 0.0;
  }
};

TEST_P(Pipeline, CornerAndOpenFacesGetEachEstimatorsAnalyticValue) {
  // A radius a quarter of the walls' size makes the corner's shadow many pixels wide.
  for (ssao::Estimator estimator : ssao::kEstimators) {
    render::FrameSettings settings = corner_settings(0.5f);
    settings.ao_settings.estimator = estimator;
    Harness h;
    ASSERT_TRUE(h.start(GetParam(), "builtin:corner", settings, corner_view()));
    const auto& params = h.renderer.ssao_params();
    ASSERT_EQ(params.end_radius - params.first_radius, 1);
    const glm::dmat4 camera_view = h.camera.view();
    const AnalyticCorner corner{params, camera_view, glm::inverse(camera_view), {128, 128}, params.radii[params.first_radius].x};
    const auto ao = h.renderer.read_ao_raw();
    const std::string name(ssao::name(estimator));
    // Per site, the mean over 5x5 pixels (all 16 turns of the tile) and each pixel against its value.
    auto site = [&](glm::dvec3 world, const char* where) {
      const glm::ivec2 centre = h.pixel_of(world);
      double gpu_sum = 0.0, expected_sum = 0.0;
      int skipped = 0;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const glm::ivec2 pixel = centre + glm::ivec2(dx, dy);
          const double gpu = ao[static_cast<size_t>(pixel.y * 128 + pixel.x)].x;
          const std::string what = name + ", " + where + ", pixel " + std::to_string(pixel.x) + "," + std::to_string(pixel.y);
          gpu_sum += gpu;
          if (estimator == ssao::Estimator::horizon) {
            const std::optional<double> expected = corner.horizon(pixel);
            if (!expected) {
              ++skipped;
              expected_sum += gpu;
              continue;
            }
            expected_sum += *expected;
            // Both round to rgba16f (2^-11 at AO in [0.5, 1)); the rest is the GPU's float trig.
            EXPECT_NEAR(gpu, *expected, 2e-3) << what;
          } else {
            const auto [low, high] = corner.hidden_share(pixel, estimator);
            expected_sum += (low + high) / 2.0;
            EXPECT_GE(gpu, low - 1e-3) << what;  // 1e-3: the half float the AO is stored in
            EXPECT_LE(gpu, high + 1e-3) << what;
            EXPECT_LE(high - low, 3.0 / params.samples) << what << ": too many samples on a boundary to judge";
          }
        }
      EXPECT_LE(skipped, 2) << name << ", " << where << ": taps on a texel edge that matters";
      std::cout << name << " " << where << ": AO " << gpu_sum / 25.0 << ", analytic " << expected_sum / 25.0 << "\n";
      return gpu_sum / 25.0;
    };
    const double corner_ao = site({0.1, 0.0, 0.1}, "floor a fifth of the radius from both walls");
    const double floor_ao = site({1.5, 0.0, 1.5}, "open floor");
    const double wall_ao = site({1.5, 1.5, 0.0}, "open wall");
    // The estimators' closed-form values on an open face, also a check on the analytic model above.
    // The hemisphere's points all lie above the tangent plane: exactly 0 (1e-3: the half float).
    // The horizon finds the tangent plane itself: taps at texel centres lie off the slice plane by up
    // to half a texel, but on the face, so they rise by nothing above it (rounding aside).
    // The sphere estimator hides the points behind the face, half the shell, less those within the
    // bias of it and those whose surface lies beyond the range check (the faces are seen at 35 and
    // 45 degrees, so points deep behind them fail it): between a quarter and a half.
    // In the corner the walls hide more than either face alone: by 0.15 at least (measured 0.27,
    // 0.52 and 0.54 above the open faces).
    if (estimator == ssao::Estimator::sphere) {
      for (double open : {floor_ao, wall_ao}) {
        EXPECT_GT(open, 0.25) << name;
        EXPECT_LT(open, 0.5) << name;
      }
    } else {
      EXPECT_LE(floor_ao, 1e-3) << name;
      EXPECT_LE(wall_ao, 1e-3) << name;
    }
    EXPECT_GT(corner_ao, std::max(floor_ao, wall_ao) + 0.15) << name;
  }
}

TEST_P(Pipeline, NoGlErrorAfterAnyPassInAnyConfiguration) {
  for (bool prepass : {true, false})
    for (bool ao : {true, false})
      for (ssao::Blur blur : {ssao::Blur::off, ssao::Blur::gaussian, ssao::Blur::bilateral, ssao::Blur::denoise})
        for (render::Picture view :
             {render::Picture::color, render::Picture::ao, render::Picture::normal, render::Picture::depth}) {
          render::FrameSettings settings = small_settings();
          settings.width = 48;
          settings.height = 32;
          settings.prepass = prepass ? render::Prepass::on : render::Prepass::off;
          settings.ao = ao;
          settings.blur.mode = blur;
          settings.output = view;
          Harness h;
          ASSERT_TRUE(h.start(GetParam(), "builtin:demo", settings));
          EXPECT_EQ(h.renderer.gl_error(), "")
              << "prepass " << prepass << " ao " << ao << " blur " << ssao::name(blur) << " view " << render::name(view);
          const render::PassTimes times = h.renderer.collect_times();
          EXPECT_EQ(times[render::Pass::depth_prepass] >= 0.0, prepass);
          EXPECT_EQ(times[render::Pass::ssao] >= 0.0, ao);
          EXPECT_EQ(times[render::Pass::blur_h] >= 0.0, ao && blur != ssao::Blur::off);
          EXPECT_GE(times[render::Pass::present], 0.0);
        }
}

TEST_P(Pipeline, DepthPrepassDoesNotChangeThePicture) {
  render::FrameSettings with = small_settings(), without = small_settings();
  with.prepass = render::Prepass::on;
  without.prepass = render::Prepass::off;
  std::vector<uint8_t> picture;
  {
    Harness a;
    ASSERT_TRUE(a.start(GetParam(), "builtin:demo", with));
    picture = a.renderer.read_color();
  }
  Harness b;
  ASSERT_TRUE(b.start(GetParam(), "builtin:demo", without));
  EXPECT_EQ(picture, b.renderer.read_color());
}

TEST_P(Pipeline, SwitchingOffASavingChangesNoPixel) {
  // aobench measures what each saving saves by turning it off; that is fair only if the saving
  // costs nothing in error: the AO and the picture must be the same either way.
  struct Saving {
    const char* name;
    void (*turn_off)(render::FrameSettings&);
  };
  const Saving savings[] = {
      {"background skip", [](render::FrameSettings& s) { s.ao_settings.skip_background = false; }},
      {"untextured G-buffer variant", [](render::FrameSettings& s) { s.untextured_variant = false; }},
  };
  for (ssao::Estimator estimator : ssao::kEstimators)
    for (const Saving& saving : savings) {
      render::FrameSettings with = small_settings();
      with.ao_settings.estimator = estimator;
      render::FrameSettings without = with;
      saving.turn_off(without);
      const std::string what = std::string(saving.name) + " off, " + std::string(ssao::name(estimator));
      Harness a;
      ASSERT_TRUE(a.start(GetParam(), "builtin:demo", with)) << what;
      Harness b;
      ASSERT_TRUE(b.start(GetParam(), "builtin:demo", without)) << what;
      const auto ao_with = a.renderer.read_ao_final(), ao_without = b.renderer.read_ao_final();
      ASSERT_EQ(ao_with.size(), ao_without.size());
      size_t different = 0;
      for (size_t i = 0; i < ao_with.size(); ++i) different += ao_with[i] != ao_without[i] ? 1 : 0;
      EXPECT_EQ(different, 0u) << what;
      EXPECT_EQ(a.renderer.read_color(), b.renderer.read_color()) << what;
      EXPECT_EQ(b.renderer.gl_error(), "") << what;
    }
}

TEST_P(Pipeline, AutomaticPrepassMeasuresBothAndKeepsTheFaster) {
  render::FrameSettings settings = small_settings();
  settings.prepass = render::Prepass::automatic;
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), "builtin:demo", settings));
  const render::PassTimes first = h.renderer.collect_times();
  EXPECT_GE(first[render::Pass::depth_prepass], 0.0);  // the first frame tries the prepass
  h.renderer.render(h.camera);
  const render::PassTimes second = h.renderer.collect_times();
  EXPECT_LT(second[render::Pass::depth_prepass], 0.0);  // the second does without
  ASSERT_GE(h.renderer.raster_ms_with_prepass(), 0.0);
  ASSERT_GE(h.renderer.raster_ms_without_prepass(), 0.0);
  h.renderer.render(h.camera);
  const render::PassTimes third = h.renderer.collect_times();
  const bool keep = h.renderer.raster_ms_with_prepass() <= h.renderer.raster_ms_without_prepass();
  EXPECT_EQ(h.renderer.prepass_in_use(), keep);
  EXPECT_EQ(third[render::Pass::depth_prepass] >= 0.0, keep);
  EXPECT_EQ(h.renderer.gl_error(), "");
}

TEST_P(Pipeline, SharedSceneWithoutNormalsRendersWithFiniteNormals) {
  render::FrameSettings settings = small_settings();
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), std::string(PLAYER_SHARED_DIR) + "/scenes/teapot-no-normals.glb", settings));
  EXPECT_EQ(h.renderer.gl_error(), "");
  const auto depth = h.renderer.read_linear_depth();
  EXPECT_GT(std::count_if(depth.begin(), depth.end(), [](float d) { return d > 0.0f; }), kSide * kSide / 8);
  for (const glm::vec3& n : h.renderer.read_view_normals()) ASSERT_FALSE(std::isnan(n.x) || std::isnan(n.y) || std::isnan(n.z));
}

// Straight down the z axis, near enough that a 2 x 2 square in the z = 0 plane fills the view.
scene::Framing square_filling_the_view() {
  scene::Framing head_on;
  head_on.azimuth_deg = 0.0;
  head_on.elevation_deg = 0.0;
  head_on.distance = 0.5;
  return head_on;
}

TEST_P(Pipeline, TheGBufferHoldsTheFacesPlaneBesideTheShadingNormal) {
  // A square facing the camera whose vertex normals all lean 20 degrees to the side, as smooth
  // normals do on a facet of a coarse mesh: the shading normal read back is the leaning one, the
  // face normal the square's own (either way round: only its plane matters to the horizon).
  constexpr float kLean = glm::radians(20.0f);
  scene::Scene built;
  built.materials = {scene::Material{}};
  scene::Mesh quad = scene::make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0);
  for (scene::Vertex& v : quad.vertices) v.normal = glm::vec3(std::sin(kLean), 0.0f, std::cos(kLean));
  scene::add_instance(built, quad);
  scene::update_bounds(built);
  render::FrameSettings settings = small_settings();
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), std::move(built), settings, square_filling_the_view()));
  const auto depth = h.renderer.read_linear_depth();
  const auto shading = h.renderer.read_view_normals();
  const auto faces = h.renderer.read_view_face_normals();
  size_t objects = 0;
  for (size_t i = 0; i < depth.size(); ++i) {
    if (!(depth[i] > 0.0f)) continue;
    ++objects;
    ASSERT_NEAR(std::abs(faces[i].z), 1.0f, 1e-4f) << "pixel " << i << ": the face faces the camera";
    ASSERT_NEAR(std::abs(shading[i].x), std::sin(kLean), 2e-3f) << "pixel " << i;
    ASSERT_NEAR(shading[i].z, std::cos(kLean), 2e-3f) << "pixel " << i;
  }
  EXPECT_EQ(objects, depth.size()) << "the square fills the view";
  EXPECT_EQ(h.renderer.gl_error(), "");
}

TEST_P(Pipeline, BaseColorTextureLandsWhereItsUvsSay) {
  // A square facing the camera with a 2x2 texture: red, green on the top row of the image (v = 0),
  // blue, white below, sampled nearest. glTF puts uv (0, 0) at the image's top-left corner.
  scene::Scene built;
  scene::Material material;
  material.base_color_texture = 0;
  built.materials = {material};
  scene::Texture texture;
  texture.width = texture.height = 2;
  texture.rgba = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255};
  texture.mag = scene::Filter::nearest;
  texture.mipmaps = false;
  built.textures = {texture};
  scene::Mesh quad = scene::make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0);
  // make_quad's uv runs up the square; flip v so the image's top row is at the top of the square.
  for (scene::Vertex& v : quad.vertices) v.uv.y = 1.0f - v.uv.y;
  scene::add_instance(built, quad);
  scene::update_bounds(built);
  render::FrameSettings settings = small_settings();
  settings.ao = false;
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), std::move(built), settings, square_filling_the_view()));
  const auto color = h.renderer.read_color();  // row 0 at the top
  auto at = [&](int x, int y) {
    return glm::ivec3(color[static_cast<size_t>((y * kSide + x) * 4)], color[static_cast<size_t>((y * kSide + x) * 4 + 1)],
                      color[static_cast<size_t>((y * kSide + x) * 4 + 2)]);
  };
  const glm::ivec3 top_left = at(16, 16), top_right = at(48, 16), bottom_left = at(16, 48), bottom_right = at(48, 48);
  EXPECT_GT(top_left.r, 100);
  EXPECT_LT(top_left.g + top_left.b, 10);
  EXPECT_GT(top_right.g, 100);
  EXPECT_LT(top_right.r + top_right.b, 10);
  EXPECT_GT(bottom_left.b, 100);
  EXPECT_LT(bottom_left.r + bottom_left.g, 10);
  EXPECT_GT(std::min({bottom_right.r, bottom_right.g, bottom_right.b}), 100);
  EXPECT_EQ(h.renderer.gl_error(), "");
}

TEST_P(Pipeline, AlphaMaskCutsWhereTheTextureIsTransparentInBothPasses) {
  // A square at z = 0 whose 2x1 texture is transparent on the left and opaque on the right, in front
  // of a larger green square at z = -1. MASK cuts the left half in the depth prepass and the
  // G-buffer alike: there the green square behind shows, at its own depth.
  for (const scene::AlphaMode mode : {scene::AlphaMode::opaque, scene::AlphaMode::mask})
    for (const render::Prepass prepass : {render::Prepass::off, render::Prepass::on}) {
      scene::Scene built;
      scene::Material front, back;
      front.base_color_texture = 0;
      front.alpha_mode = mode;
      front.alpha_cutoff = 0.5f;
      back.base_color = {0, 1, 0, 1};
      built.materials = {front, back};
      scene::Texture texture;
      texture.width = 2;
      texture.height = 1;
      texture.rgba = {255, 0, 0, 0, 255, 0, 0, 255};
      texture.mag = scene::Filter::nearest;
      texture.mipmaps = false;
      built.textures = {texture};
      scene::add_instance(built, scene::make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0));
      scene::add_instance(built, scene::make_quad({-3, -3, -1}, {6, 0, 0}, {0, 6, 0}, 1));
      scene::update_bounds(built);
      render::FrameSettings settings = small_settings();
      settings.ao = false;
      settings.prepass = prepass;
      scene::Framing framing = square_filling_the_view();
      framing.distance = 1.5;
      Harness h;
      ASSERT_TRUE(h.start(GetParam(), std::move(built), settings, framing));
      const auto color = h.renderer.read_color();  // row 0 at the top
      const auto depth = h.renderer.read_linear_depth();
      const glm::ivec2 left = h.pixel_of({-0.5, 0.0, 0.0}), right = h.pixel_of({0.5, 0.0, 0.0});
      auto rgb = [&](glm::ivec2 p) {
        const size_t at = static_cast<size_t>(((kSide - 1 - p.y) * kSide + p.x) * 4);
        return glm::ivec3(color[at], color[at + 1], color[at + 2]);
      };
      auto depth_at = [&](glm::ivec2 p) { return depth[static_cast<size_t>(p.y * kSide + p.x)]; };
      const std::string what =
          std::string(mode == scene::AlphaMode::mask ? "mask" : "opaque") + (prepass == render::Prepass::on ? ", prepass" : "");
      EXPECT_GT(rgb(right).r, 100) << what;
      EXPECT_LT(rgb(right).g, 10) << what;
      if (mode == scene::AlphaMode::mask) {
        EXPECT_GT(rgb(left).g, 100) << what << ": the green square behind shows through the cut";
        EXPECT_LT(rgb(left).r, 10) << what;
        EXPECT_GT(depth_at(left), depth_at(right) + 0.5f) << what << ": the cut keeps the depth of what is behind";
      } else {
        EXPECT_GT(rgb(left).r, 100) << what;
        EXPECT_NEAR(depth_at(left), depth_at(right), 0.05f) << what;
      }
      EXPECT_EQ(h.renderer.gl_error(), "") << what;
    }
}

TEST_P(Pipeline, UnlitMaterialsShowTheirBaseColourNeitherLitNorOccluded) {
  // Two squares meeting in a corner (so the AO is well above zero there), each of base colour
  // (0.2, 0.6, 0.4): unlit, every pixel is that colour sRGB-encoded, the corner included; lit, it is not.
  for (const bool unlit : {true, false}) {
    scene::Scene built;
    scene::Material material;
    material.base_color = {0.2f, 0.6f, 0.4f, 1.0f};
    material.unlit = unlit;
    built.materials = {material};
    scene::add_instance(built, scene::make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 0));
    scene::add_instance(built, scene::make_quad({-1, -1, 0}, {0, 0, 2}, {2, 0, 0}, 0));
    scene::update_bounds(built);
    render::FrameSettings settings = small_settings();
    Harness h;
    ASSERT_TRUE(h.start(GetParam(), std::move(built), settings));
    const auto color = h.renderer.read_color();
    const auto depth = h.renderer.read_linear_depth();
    auto srgb = [](float linear) {
      return static_cast<int>(
          std::lround(255.0 * (linear <= 0.0031308 ? linear * 12.92 : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055)));
    };
    const glm::ivec3 expected(srgb(0.2f), srgb(0.6f), srgb(0.4f));
    size_t surface = 0, differing = 0;
    for (int y = 0; y < kSide; ++y)
      for (int x = 0; x < kSide; ++x) {
        if (depth[static_cast<size_t>((kSide - 1 - y) * kSide + x)] <= 0.0f) continue;
        ++surface;
        const size_t at = static_cast<size_t>((y * kSide + x) * 4);
        const glm::ivec3 got(color[at], color[at + 1], color[at + 2]);
        const glm::ivec3 off = glm::abs(got - expected);
        if (std::max({off.x, off.y, off.z}) > 1) ++differing;
      }
    ASSERT_GT(surface, 1000u);
    if (unlit)
      EXPECT_EQ(differing, 0u) << "unlit pixels off their base colour";
    else
      EXPECT_GT(differing, surface / 2) << "lit pixels are shaded";
    EXPECT_EQ(h.renderer.gl_error(), "");
  }
}

INSTANTIATE_TEST_SUITE_P(Platforms, Pipeline, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace
