// The shaded image's light on a real context: glTF's metallic-roughness BRDF under image-based
// lighting (gles_shaders/pbr.glsl, present.frag), checked where the answer is known without the
// renderer: white furnaces, emission, and what the SSAO term may and may not darken.
#include "harness.h"
#include "scene/environment.h"
#include "scene/procedural.h"

#include <cmath>
#include <memory>

namespace {

using test::Harness;

constexpr int kSide = 96;

double srgb_to_linear(int value) {
  const double c = value / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// A sphere of one material under `environment`, lit by nothing else, without AO.
struct Shot {
  std::vector<uint8_t> color;
  std::vector<float> depth;
};

Shot sphere_under(const std::string& platform, const scene::Material& material, std::shared_ptr<const scene::Environment> environment,
                  float key_light = 0.0f, bool ao = false) {
  scene::Scene built;
  built.materials = {material};
  scene::add_instance(built, scene::make_sphere({0, 0, 0}, 1.0f, 48, 0));
  built.environment = std::move(environment);
  scene::update_bounds(built);
  render::FrameSettings settings;
  settings.width = settings.height = kSide;
  settings.check_errors = true;
  settings.ao = ao;
  settings.key_light = key_light;
  Harness h;
  EXPECT_TRUE(h.start(platform, std::move(built), settings));
  EXPECT_EQ(h.renderer.gl_error(), "");
  return {h.renderer.read_color(), h.renderer.read_linear_depth()};
}

// Every sphere pixel's linear value per channel, against `expected`: the largest relative error.
double worst_relative_error(const Shot& shot, double expected, size_t* pixels = nullptr) {
  double worst = 0.0;
  size_t count = 0;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      if (shot.depth[static_cast<size_t>((kSide - 1 - y) * kSide + x)] <= 0.0f) continue;
      ++count;
      for (int c = 0; c < 3; ++c) {
        const double value = srgb_to_linear(shot.color[static_cast<size_t>((y * kSide + x) * 4 + c)]);
        worst = std::max(worst, std::abs(value - expected) / expected);
      }
    }
  if (pixels) *pixels = count;
  return worst;
}

class Shading : public ::testing::TestWithParam<std::string> {};

// A white diffuse sphere and rough and smooth white metal spheres under a uniform white
// environment shade to the environment's value (within 2%, about one step of the 8-bit output at
// 0.5): the split-sum's multiple-scattering compensation keeps the energy a rough lobe would lose.
TEST_P(Shading, WhiteFurnacesShadeToTheEnvironment) {
  const auto white = std::make_shared<const scene::Environment>(scene::uniform_environment(glm::vec3(0.5f)));
  struct Case {
    const char* what;
    float metallic, roughness;
  };
  for (const Case c : {Case{"white diffuse", 0.0f, 1.0f}, Case{"white diffuse, glossy", 0.0f, 0.3f},
                       Case{"rough white metal", 1.0f, 1.0f}, Case{"half-rough white metal", 1.0f, 0.5f},
                       Case{"polished white metal", 1.0f, 0.05f}}) {
    scene::Material material;
    material.base_color = glm::vec4(1.0f);
    material.metallic = c.metallic;
    material.roughness = c.roughness;
    size_t pixels = 0;
    const double error = worst_relative_error(sphere_under(GetParam(), material, white), 0.5, &pixels);
    EXPECT_GT(pixels, size_t{kSide * kSide / 5}) << c.what;  // the framed sphere covers about a quarter
    EXPECT_LT(error, 0.02) << c.what;
  }
}

// Emission adds to the light, at any brightness KHR_materials_emissive_strength gives: a black,
// rough sphere in a black environment shows its emission and nothing else.
TEST_P(Shading, EmissionIsAddedAsItIs) {
  const auto black = std::make_shared<const scene::Environment>(scene::uniform_environment(glm::vec3(0.0f)));
  scene::Material material;
  material.base_color = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  material.metallic = 0.0f;
  material.emissive = glm::vec3(0.25f);
  EXPECT_LT(worst_relative_error(sphere_under(GetParam(), material, black), 0.25), 0.02);
  material.emissive = glm::vec3(0.0f);
  const Shot dark = sphere_under(GetParam(), material, black);
  EXPECT_EQ(worst_relative_error(dark, 1.0), 1.0);  // every channel 0: relative error exactly 1
}

INSTANTIATE_TEST_SUITE_P(Platforms, Shading, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace
