// Blended materials (glTF's alphaMode BLEND) on a real context: drawn after the opaque image by
// the forward pass, "over" it, farthest first, and hidden behind opaque surfaces.
#include "harness.h"
#include "scene/procedural.h"

#include <cmath>

namespace {

using test::Harness;

class Blending : public ::testing::TestWithParam<std::string> {};

double srgb_code(double linear) {
  return 255.0 * (linear <= 0.0031308 ? linear * 12.92 : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055);
}

// Seen head on over a black background: an opaque blue quad on the left half at z = 0; a half
// transparent red quad over the top half in front of it (z = 0.5) and a half transparent green
// one over everything behind it (z = -0.5). The red quad comes first in the scene, so only the
// back-to-front sort draws the green one first where both are seen. Unlit, so each colour is
// what it is: where the framebuffer encodes sRGB the blend is in linear light; where the shader
// encodes (osmesa) it is between the encoded values.
TEST_P(Blending, BlendedSurfacesAreDrawnOverTheOpaqueImageFarthestFirst) {
  scene::Scene built;
  auto unlit = [](glm::vec4 color, scene::AlphaMode mode) {
    scene::Material material;
    material.base_color = color;
    material.unlit = true;
    material.alpha_mode = mode;
    return material;
  };
  built.materials = {scene::Material{}, unlit({0, 0, 1, 1}, scene::AlphaMode::opaque),
                     unlit({1, 0, 0, 0.5f}, scene::AlphaMode::blend), unlit({0, 1, 0, 0.5f}, scene::AlphaMode::blend)};
  scene::add_instance(built, scene::make_quad({-1.5f, 0.0f, 0.5f}, {3, 0, 0}, {0, 1.5f, 0}, 2));  // red, front, top
  scene::add_instance(built, scene::make_quad({-2.0f, -2.0f, -0.5f}, {4, 0, 0}, {0, 4, 0}, 3));   // green, back
  scene::add_instance(built, scene::make_quad({-2.0f, -2.0f, 0.0f}, {2, 0, 0}, {0, 4, 0}, 1));    // blue, left
  scene::update_bounds(built);
  render::FrameSettings settings;
  settings.width = settings.height = 96;
  settings.check_errors = true;
  settings.ao = false;
  settings.background = glm::vec3(0.0f);
  scene::Framing framing;
  framing.azimuth_deg = 0.0;
  framing.elevation_deg = 0.0;
  framing.distance = 0.6;
  Harness h;
  ASSERT_TRUE(h.start(GetParam(), std::move(built), settings, framing));
  EXPECT_EQ(h.renderer.gl_error(), "");
  const bool linear_blending = h.target().srgb;
  const std::vector<uint8_t> color = h.renderer.read_color();
  auto at = [&](glm::dvec3 world) {
    const glm::ivec2 pixel = h.pixel_of(world);
    const size_t i = static_cast<size_t>(((settings.height - 1 - pixel.y) * settings.width + pixel.x) * 4);
    return glm::dvec3(color[i], color[i + 1], color[i + 2]);
  };
  // Each channel as blended: a list of (colour, alpha) from the back, over black.
  auto expected = [&](std::initializer_list<std::pair<glm::dvec3, double>> layers) {
    glm::dvec3 value(0.0);
    for (const auto& [c, alpha] : layers) {
      const glm::dvec3 source = linear_blending ? c : glm::dvec3(srgb_code(c.r), srgb_code(c.g), srgb_code(c.b)) / 255.0;
      value = source * alpha + value * (1.0 - alpha);
    }
    return linear_blending ? glm::dvec3(srgb_code(value.r), srgb_code(value.g), srgb_code(value.b)) : value * 255.0;
  };
  const glm::dvec3 red(1, 0, 0), green(0, 1, 0), blue(0, 0, 1);
  struct Probe {
    const char* what;
    glm::dvec3 world;
    glm::dvec3 expected;
  };
  for (const Probe& probe :
       {Probe{"red over blue (the green behind the blue is hidden)", {-0.7, 0.7, 0.5}, expected({{blue, 1.0}, {red, 0.5}})},
        Probe{"red over green, green drawn first", {0.7, 0.7, 0.5}, expected({{green, 0.5}, {red, 0.5}})},
        Probe{"blue alone: the green behind it is hidden", {-0.7, -0.7, 0.0}, expected({{blue, 1.0}})},
        Probe{"green over the background", {0.7, -0.7, -0.5}, expected({{green, 0.5}})}}) {
    const glm::dvec3 seen = at(probe.world);
    // llvmpipe's sRGB framebuffer encoder is up to about three steps off (shading_test.cpp).
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(seen[c], probe.expected[c], 4.0) << probe.what << ", channel " << c << " (sRGB codes)";
  }
}

INSTANTIATE_TEST_SUITE_P(Platforms, Blending, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace
