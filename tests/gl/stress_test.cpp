// Numerical stress: the same scene far from the origin, scaled over eight orders of magnitude, with
// extreme near/far ratios, and degenerate geometry. AO must stay within a stated bound of the
// untouched case, and no buffer may hold NaN or infinity.
#include "harness.h"
#include "scene/procedural.h"
#include "ssao/reference.h"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <iostream>

namespace {

using test::Harness;

constexpr int kSide = 96;

render::FrameSettings stress_settings() {
  render::FrameSettings settings;
  settings.width = settings.height = kSide;
  settings.check_errors = true;
  settings.blur.mode = ssao::Blur::off;          // compare the estimator itself
  settings.ao_settings.half_resolution = false;  // pixel for pixel against the untouched case
  settings.ao_settings.samples = 16;
  settings.temporal = false;  // one frame's numerics; TemporalAccumulationStaysFiniteAtEveryNearFarRatio below
  return settings;
}

scene::Scene spheres() {
  return *scene::make_builtin("spheres");
}

// What a picture's AO and coverage were; taken while its context is current, since each Harness
// has its own context and GL names mean nothing in another one.
struct Snapshot {
  std::vector<glm::vec2> ao;
  std::vector<float> depth;
};

Snapshot snapshot(const Harness& h) {
  return {h.renderer.read_ao_final(), h.renderer.read_linear_depth()};
}

Snapshot render_snapshot(const std::string& platform_name, scene::Scene scene) {
  Harness h;
  EXPECT_TRUE(h.start(platform_name, std::move(scene), stress_settings()));
  return snapshot(h);
}

struct Difference {
  double mean = 0.0;  // over pixels that are objects in both pictures
  // Share of those pixels differing by more than 1/16: one sample of the point-sampled estimators
  // (16 samples), a sixth of a slice of the default horizon estimator (16 taps: 2 slices of 8).
  double worst_share = 0.0;
  size_t coverage_changed = 0;
};

Difference difference(const Snapshot& a, const Snapshot& b) {
  Difference d;
  size_t both = 0, off = 0;
  for (size_t i = 0; i < a.ao.size(); ++i) {
    if ((a.depth[i] > 0.0f) != (b.depth[i] > 0.0f)) ++d.coverage_changed;
    if (a.depth[i] <= 0.0f || b.depth[i] <= 0.0f) continue;
    const double delta = std::abs(a.ao[i].x - b.ao[i].x);
    d.mean += delta;
    off += delta > 1.0 / 16.0 + 1e-3 ? 1 : 0;
    ++both;
  }
  EXPECT_GT(both, a.ao.size() / 10) << "the pictures must show the scene";
  d.mean /= static_cast<double>(std::max<size_t>(both, 1));
  d.worst_share = static_cast<double>(off) / static_cast<double>(std::max<size_t>(both, 1));
  return d;
}

void expect_all_finite(const Harness& h, const std::string& what) {
  for (float v : h.renderer.read_linear_depth()) ASSERT_TRUE(std::isfinite(v) && v >= 0.0f) << what;
  for (const auto& normals : {h.renderer.read_view_normals(), h.renderer.read_view_face_normals()})
    for (const glm::vec3& n : normals) ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z)) << what;
  for (const auto& buffer : {h.renderer.read_ao_raw(), h.renderer.read_ao_final()})
    for (const glm::vec2& ao : buffer) {
      ASSERT_TRUE(std::isfinite(ao.x) && std::isfinite(ao.y)) << what;
      ASSERT_GE(ao.x, 0.0f) << what;
      ASSERT_LE(ao.x, 1.0f) << what;
    }
}

class Stress : public ::testing::TestWithParam<std::string> {};

// Bounds for a picture of the same scene whose only change is an exact similarity transform: the
// rasteriser may move a silhouette pixel, which moves what a neighbour's samples or taps read. The
// default estimator is the horizon's (stress_settings leaves it): continuous in the tap depths, it
// changes by a tap's share of a slice when a tap's texel moves across a silhouette; the point-sampled
// estimators flip a sample lying within rounding of a depth boundary (1/16). Mean AO difference
// 0.005; at most 2% of pixels off by more than 1/16. DegenerateGeometry and Mediump run every
// estimator; the transform tests run the default and, for the paper's sphere, the same bounds
// (EveryEstimatorKeepsTheBoundsWhenScaled).
constexpr double kMeanBound = 0.005, kShareBound = 0.02;

TEST_P(Stress, TranslatedFarFromTheOriginByNodeTransforms) {
  const Snapshot reference = render_snapshot(GetParam(), spheres());
  for (double offset : {1e3, 1e5, 1e7}) {
    scene::Scene moved = spheres();
    for (scene::Instance& instance : moved.instances)
      instance.world = glm::translate(glm::dmat4(1.0), glm::dvec3(offset, -offset, offset)) * instance.world;
    scene::update_bounds(moved);
    Harness h;
    ASSERT_TRUE(h.start(GetParam(), std::move(moved), stress_settings()));
    const Difference d = difference(reference, snapshot(h));
    EXPECT_LE(d.mean, kMeanBound) << "offset " << offset;
    EXPECT_LE(d.worst_share, kShareBound) << "offset " << offset;
    expect_all_finite(h, "offset " + std::to_string(offset));
  }
}

scene::Scene baked_far_away(double distance) {
  scene::Scene baked = spheres();
  const glm::dvec3 offset(distance, -distance, distance);
  for (scene::Instance& instance : baked.instances) {
    scene::Mesh mesh = baked.meshes[static_cast<size_t>(instance.mesh)];
    for (scene::Vertex& v : mesh.vertices)
      v.position = glm::vec3(glm::dvec3(instance.world * glm::dvec4(v.position, 1.0)) + offset);
    mesh.min = glm::vec3(glm::dvec3(instance.world * glm::dvec4(mesh.min, 1.0)) + offset);
    mesh.max = glm::vec3(glm::dvec3(instance.world * glm::dvec4(mesh.max, 1.0)) + offset);
    baked.meshes.push_back(mesh);
    instance = {static_cast<int>(baked.meshes.size()) - 1, glm::dmat4(1.0)};
  }
  scene::recenter_meshes(baked);
  return baked;
}

TEST_P(Stress, TranslatedFarFromTheOriginInTheVerticesThemselves) {
  // Coordinates baked into float vertices (as a glTF file would store them). Re-centring each mesh
  // at load keeps what the floats still hold (without it the scene vanishes at 1e5): at 1e5 a float's
  // step is 0.008, 1.6% of a sphere's radius, and the bound still holds; at 1e7 the step is 1 and the
  // spheres are gone (with the default horizon estimator, mean difference 0.10, 35% of pixels off by
  // more than 1/16: printed, beyond the bound). No camera trick restores precision the file's floats never had.
  const Snapshot reference = render_snapshot(GetParam(), spheres());
  for (double distance : {1e3, 1e5, 1e7}) {
    Harness h;
    ASSERT_TRUE(h.start(GetParam(), baked_far_away(distance), stress_settings()));
    const Difference d = difference(reference, snapshot(h));
    expect_all_finite(h, "baked offset " + std::to_string(distance));
    if (distance <= 1e5) {
      EXPECT_LE(d.mean, kMeanBound);
      EXPECT_LE(d.worst_share, kShareBound);
    } else {
      std::cout << "baked offset " << distance << ": mean AO difference " << d.mean << ", share off by more than a sample "
                << d.worst_share << ", coverage changed at " << d.coverage_changed << " pixels (beyond the bound)\n";
    }
  }
}

TEST_P(Stress, ScaledFromATenThousandthToTenThousandTimes) {
  const Snapshot reference = render_snapshot(GetParam(), spheres());
  for (double scale : {1e-4, 1e-2, 1e2, 1e4}) {
    scene::Scene scaled = spheres();
    for (scene::Instance& instance : scaled.instances)
      instance.world = glm::scale(glm::dmat4(1.0), glm::dvec3(scale)) * instance.world;
    scene::update_bounds(scaled);
    Harness h;
    ASSERT_TRUE(h.start(GetParam(), std::move(scaled), stress_settings()));
    const Difference d = difference(reference, snapshot(h));
    EXPECT_LE(d.mean, kMeanBound) << "scale " << scale;
    EXPECT_LE(d.worst_share, kShareBound) << "scale " << scale;
    expect_all_finite(h, "scale " + std::to_string(scale));
  }
}

TEST_P(Stress, EveryEstimatorKeepsTheBoundsWhenScaled) {
  for (ssao::Estimator estimator : ssao::kEstimators) {
    render::FrameSettings settings = stress_settings();
    settings.ao_settings.estimator = estimator;
    Snapshot reference;
    {
      Harness h;
      ASSERT_TRUE(h.start(GetParam(), spheres(), settings));
      reference = snapshot(h);
    }
    for (double scale : {1e-3, 1e3}) {
      scene::Scene scaled = spheres();
      for (scene::Instance& instance : scaled.instances)
        instance.world = glm::scale(glm::dmat4(1.0), glm::dvec3(scale)) * instance.world;
      scene::update_bounds(scaled);
      Harness h;
      ASSERT_TRUE(h.start(GetParam(), std::move(scaled), settings));
      const Difference d = difference(reference, snapshot(h));
      const std::string what = std::string(ssao::name(estimator)) + " at scale " + std::to_string(scale);
      EXPECT_LE(d.mean, kMeanBound) << what;
      EXPECT_LE(d.worst_share, kShareBound) << what;
      expect_all_finite(h, what);
    }
  }
}

TEST_P(Stress, NearFarRatiosUpToAMillion) {
  const Snapshot reference = render_snapshot(GetParam(), spheres());
  for (double ratio : {1e3, 1e4, 1e5, 1e6}) {
    Harness h;
    ASSERT_TRUE(h.start(GetParam(), spheres(), stress_settings()));
    scene::Camera camera = h.camera;
    camera.near = camera.far / ratio;  // linear depth is stored apart from the depth buffer
    h.camera = camera;
    h.renderer.render(camera);
    const Difference d = difference(reference, snapshot(h));
    EXPECT_LE(d.mean, kMeanBound) << "near/far 1/" << ratio;
    EXPECT_LE(d.worst_share, kShareBound) << "near/far 1/" << ratio;
    expect_all_finite(h, "near/far ratio " + std::to_string(ratio));
  }
}

// Temporal accumulation reprojects each pixel through the inverse view and the previous
// projection. Over a slow turn of the camera, its average at near/far ratios up to a million must
// stay what it is at the usual ratio, and finite.
TEST_P(Stress, TemporalAccumulationStaysFiniteAtEveryNearFarRatio) {
  render::FrameSettings settings = stress_settings();
  settings.temporal = true;
  settings.history = 8;
  auto accumulated = [&](Harness& h, double ratio) {
    EXPECT_TRUE(h.start(GetParam(), spheres(), settings));
    h.renderer.targets().reset_history();
    for (int frame = 0; frame < 8; ++frame) {
      scene::Framing framing;
      framing.azimuth_deg = 30.0 + frame;
      scene::Camera camera = scene::frame(h.scene.bounds, framing, kSide, kSide);
      if (ratio > 0.0) camera.near = camera.far / ratio;
      h.renderer.render(camera);
    }
    EXPECT_EQ(h.renderer.gl_error(), "");
    return snapshot(h);
  };
  Harness usual;
  const Snapshot reference = accumulated(usual, 0.0);
  for (double ratio : {1e3, 1e6}) {
    Harness h;
    const Difference d = difference(reference, accumulated(h, ratio));
    EXPECT_LE(d.mean, kMeanBound) << "near/far 1/" << ratio;
    EXPECT_LE(d.worst_share, kShareBound) << "near/far 1/" << ratio;
    expect_all_finite(h, "temporal at near/far ratio " + std::to_string(ratio));
  }
}

TEST_P(Stress, DegenerateGeometryGivesBoundedAoAndNoNaN) {
  scene::Scene scene = spheres();
  scene::Mesh junk = scene::make_quad({-2, 0.01f, -2}, {1, 0, 0}, {0, 0, 1}, 0);
  // A zero-area triangle (one point), a collinear one, a duplicate of a visible triangle, zero
  // normals and normals a thousand times too long.
  const auto base = static_cast<uint32_t>(junk.vertices.size());
  junk.vertices.push_back({{0.5f, 0.5f, 0.5f}, {0, 0, 0}, {0, 0}});
  junk.vertices.push_back({{0.0f, 0.2f, 0.0f}, {0, 1000, 0}, {0, 0}});
  junk.vertices.push_back({{0.5f, 0.2f, 0.0f}, {0, 0, 0}, {0, 0}});
  junk.vertices.push_back({{1.0f, 0.2f, 0.0f}, {0, 1e-30f, 0}, {0, 0}});
  junk.indices.insert(junk.indices.end(), {base, base, base, base + 1, base + 2, base + 3, 0, 1, 2});
  for (scene::Vertex& v : junk.vertices) v.normal *= 1000.0f;
  junk.vertices[0].normal = glm::vec3(0.0f);
  scene::add_instance(scene, junk);
  // A speck of geometry 1e18 units away stretches the bounds, the far plane and the radius.
  scene::Mesh far_away = scene::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0);
  scene::add_instance(scene, far_away, glm::translate(glm::dmat4(1.0), glm::dvec3(1e18, 0, 0)));
  scene::update_bounds(scene);
  for (ssao::Estimator estimator : ssao::kEstimators) {
    render::FrameSettings settings = stress_settings();
    settings.ao_settings.estimator = estimator;
    settings.blur.mode = ssao::Blur::bilateral;
    Harness h;
    ASSERT_TRUE(h.start(GetParam(), scene, settings));
    EXPECT_EQ(h.renderer.gl_error(), "");
    expect_all_finite(h, std::string(ssao::name(estimator)));
    // And the same junk at a sane scale, so the degenerate triangles are actually on screen.
    scene::Scene near_only = scene;
    near_only.instances.pop_back();
    scene::update_bounds(near_only);
    Harness n;
    ASSERT_TRUE(n.start(GetParam(), std::move(near_only), settings));
    EXPECT_EQ(n.renderer.gl_error(), "");
    expect_all_finite(n, std::string(ssao::name(estimator)) + " near");
  }
}

TEST(Mediump, VariantStaysWithinTheBoundOfHighp) {
  // Mesa's llvmpipe computes most of its mediump at 32 bits, so the fp16 variant is emulated on the
  // CPU: the reference rounds exactly what ssao.comp's AO_MEDIUMP variant declares mediump (the
  // per-sample offsets and depth differences, all relative to the shaded point) and runs on the
  // G-buffer the GPU drew. Same bound as the other stress tests. Scenes near the origin and scaled by
  // 1e3 and 1e-3: fp16 holds 11 significant bits whatever the scale, and nothing per sample may
  // depend on the scene's units. That the rounding is really applied: the point-sampled estimators'
  // emulation must differ from highp somewhere (a point sample flips only near a boundary, so at some
  // scale, not at every one); the horizon keeps every per-tap value highp, so its must not.
  size_t changed_by_estimator[std::size(ssao::kEstimators)] = {};
  for (double scale : {1.0, 1e3, 1e-3}) {
    for (ssao::Estimator estimator : ssao::kEstimators) {
      scene::Scene scaled = spheres();
      for (scene::Instance& instance : scaled.instances)
        instance.world = glm::scale(glm::dmat4(1.0), glm::dvec3(scale)) * instance.world;
      scene::update_bounds(scaled);
      render::FrameSettings settings = stress_settings();
      settings.ao_settings.estimator = estimator;
      Harness h;
      ASSERT_TRUE(h.start("egl", std::move(scaled), settings));
      const auto depth = h.renderer.read_linear_depth();
      const auto chain = ssao::build_depth_chain(depth, kSide, kSide);
      const auto normals = h.renderer.read_view_normals();
      const auto faces = h.renderer.read_view_face_normals();
      const auto high =
          ssao::reference_ssao(chain, normals, faces, h.renderer.ssao_params(), h.renderer.inverse_far(), estimator, false);
      const auto medium =
          ssao::reference_ssao(chain, normals, faces, h.renderer.ssao_params(), h.renderer.inverse_far(), estimator, true);
      double sum = 0.0;
      size_t objects = 0, off = 0, changed = 0;
      for (size_t i = 0; i < high.size(); ++i) {
        if (depth[i] <= 0.0f) continue;
        const double delta = std::abs(high[i].x - medium[i].x);
        changed += delta > 0.0 ? 1 : 0;
        sum += delta;
        off += delta > 1.0 / 16.0 + 1e-3 ? 1 : 0;
        ++objects;
      }
      ASSERT_GT(objects, high.size() / 10);
      const std::string what = std::string(ssao::name(estimator)) + " at scale " + std::to_string(scale);
      std::cout << "mediump vs highp, " << what << ": mean AO difference " << sum / static_cast<double>(objects)
                << ", share off by more than a sample " << static_cast<double>(off) / static_cast<double>(objects) << "\n";
      EXPECT_LE(sum / static_cast<double>(objects), kMeanBound) << what;
      EXPECT_LE(static_cast<double>(off) / static_cast<double>(objects), kShareBound) << what;
      changed_by_estimator[static_cast<size_t>(estimator)] += changed;
    }
  }
  for (ssao::Estimator estimator : ssao::kEstimators) {
    const size_t changed = changed_by_estimator[static_cast<size_t>(estimator)];
    if (estimator == ssao::Estimator::horizon)
      EXPECT_EQ(changed, 0u) << "horizon: its taps are highp in both variants";
    else
      EXPECT_GT(changed, 0u) << ssao::name(estimator) << ": the fp16 emulation changed nothing";
  }
}

INSTANTIATE_TEST_SUITE_P(Platforms, Stress, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace
