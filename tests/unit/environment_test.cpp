// Image-based lighting's CPU side (player/scene/include/scene/environment.h): the conventions it
// documents, its integrals against brute force, and the files it refuses.
#include "scene/environment.h"
#include "scene/load.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <thread>

namespace {

namespace fs = std::filesystem;
constexpr double kPi = 3.14159265358979323846;

const glm::vec3 kAxes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
const char* const kAxisNames[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

// Directions spread over the sphere, the same on every run.
std::vector<glm::vec3> directions(int count) {
  std::mt19937 rng(7);
  std::normal_distribution<float> normal;
  std::vector<glm::vec3> out(kAxes, kAxes + 6);
  while (int(out.size()) < count) {
    const glm::vec3 d(normal(rng), normal(rng), normal(rng));
    if (glm::length(d) > 1e-3f) out.push_back(glm::normalize(d));
  }
  return out;
}

// An equirectangular image of `radiance(direction)` at its pixel centres.
template <class F>
std::vector<float> equirect(int width, int height, const F& radiance) {
  std::vector<float> rgb(std::size_t(width) * height * 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glm::vec3 value = radiance(scene::equirect_direction((x + 0.5f) / width, (y + 0.5f) / height));
      for (int c = 0; c < 3; ++c) rgb[(std::size_t(y) * width + x) * 3 + c] = value[c];
    }
  return rgb;
}

// The mean of a cube level over the sphere, each texel weighted by its solid angle.
glm::dvec3 level_mean(const scene::Environment& env, int level) {
  const int size = env.face_size >> level;
  glm::dvec3 sum(0.0);
  double weights = 0;
  for (int face = 0; face < 6; ++face)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        const double sc = 2 * (x + 0.5) / size - 1, tc = 2 * (y + 0.5) / size - 1;
        const double weight = 1 / std::pow(1 + sc * sc + tc * tc, 1.5);
        const float* p = env.specular[level].data() + ((std::size_t(face) * size + y) * size + x) * 3;
        sum += weight * glm::dvec3(p[0], p[1], p[2]);
        weights += weight;
      }
  return sum / weights;
}

TEST(Environment, AUniformEnvironmentLightsEveryNormalAndEveryLevelWithItsRadiance) {
  const glm::vec3 radiance(0.5f, 1.0f, 2.0f);
  const scene::Environment env = scene::uniform_environment(radiance);
  EXPECT_EQ(env.face_size, 32);
  ASSERT_EQ(env.levels(), 6);
  for (int l = 0; l < env.levels(); ++l)
    ASSERT_EQ(env.specular[l].size(), std::size_t(6) * (32 >> l) * (32 >> l) * 3) << "level " << l;
  for (const glm::vec3& n : directions(200)) {
    const glm::vec3 diffuse = scene::diffuse_irradiance(env, n);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(diffuse[c], radiance[c], 0.005f * radiance[c]) << "normal " << n.x << " " << n.y << " " << n.z;
    for (int l = 0; l < env.levels(); ++l) {
      const glm::vec3 specular = scene::sample_specular(env, n, float(l) / float(env.levels() - 1));
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(specular[c], radiance[c], 0.01f * radiance[c]) << "level " << l;
    }
  }
  // Every texel, not only what the directions above happen to read.
  for (int l = 0; l < env.levels(); ++l)
    for (std::size_t i = 0; i < env.specular[l].size(); ++i)
      ASSERT_NEAR(env.specular[l][i], radiance[i % 3], 0.01f * radiance[i % 3]) << "level " << l << " float " << i;
}

// The split sum's table in a white furnace (F0 = 1): A + B is GGX's single-scattering directional
// albedo, 1 for a mirror and less for a rough surface, whose light scattered more than once is lost.
TEST(Environment, SplitSumLutIsOneForAMirrorAndLessWhenRough) {
  const int size = 32;
  const std::vector<glm::vec2> lut = scene::split_sum_lut(size, 512);
  ASSERT_EQ(lut.size(), std::size_t(size * size));
  for (const glm::vec2& entry : lut) {
    ASSERT_TRUE(std::isfinite(entry.x) && std::isfinite(entry.y));
    EXPECT_GE(entry.x, 0.0f);
    EXPECT_GE(entry.y, 0.0f);
    EXPECT_LE(entry.x + entry.y, 1.01f);
  }
  for (int x = 0; x < size; ++x) EXPECT_NEAR(lut[x].x + lut[x].y, 1.0f, 0.01f) << "n.v " << (x + 0.5f) / size;
  for (int y = size / 2; y < size; ++y)
    for (int x = 0; x < size; ++x) EXPECT_LT(lut[y * size + x].x + lut[y * size + x].y, 0.99f) << "x " << x << " y " << y;
  // Looking straight at a smooth surface Schlick's Fresnel is F0 alone: all A, no B.
  const glm::vec2 normal_incidence = lut[size - 1];
  EXPECT_GT(normal_incidence.x, 0.99f);
  EXPECT_LT(normal_incidence.y, 0.01f);
}

// A and B of GGX with height-correlated Smith and Schlick's Fresnel at n.v and perceptual roughness,
// by brute force: uniform hemisphere sampling on a fine grid in (cos theta, phi), not importance
// sampling, so an error in the table's sampling or its pdf shows.
glm::dvec2 brute_force_dfg(double n_dot_v, double roughness) {
  const int rings = 1500, segments = 3000;
  const double alpha = roughness * roughness, a2 = alpha * alpha;
  const glm::dvec3 v(std::sqrt(1 - n_dot_v * n_dot_v), 0, n_dot_v);
  const double d_omega = (1.0 / rings) * (2 * kPi / segments);
  glm::dvec2 sum(0.0);
  for (int i = 0; i < rings; ++i) {
    const double n_dot_l = (i + 0.5) / rings, sin_l = std::sqrt(1 - n_dot_l * n_dot_l);
    const double visibility =
        0.5 / (n_dot_l * std::sqrt(n_dot_v * n_dot_v * (1 - a2) + a2) + n_dot_v * std::sqrt(n_dot_l * n_dot_l * (1 - a2) + a2));
    for (int j = 0; j < segments; ++j) {
      const double phi = (j + 0.5) / segments * 2 * kPi;
      const glm::dvec3 l(sin_l * std::cos(phi), sin_l * std::sin(phi), n_dot_l);
      const glm::dvec3 h = glm::normalize(l + v);
      const double f = (a2 - 1) * h.z * h.z + 1, d = a2 / (kPi * f * f);
      const double fresnel = std::pow(1 - glm::dot(v, h), 5.0);
      const double brdf_cos = d * visibility * n_dot_l * d_omega;
      sum += glm::dvec2((1 - fresnel) * brdf_cos, fresnel * brdf_cos);
    }
  }
  return sum;
}

TEST(Environment, SplitSumLutMatchesBruteForceIntegration) {
  const int size = 32;
  const std::vector<glm::vec2> lut = scene::split_sum_lut(size, 512);
  const std::pair<int, int> entries[] = {{2, 8}, {8, 16}, {2, 24}, {16, 24}, {8, 31}, {31, 31}};
  for (const auto& [x, y] : entries) {
    const glm::dvec2 expected = brute_force_dfg((x + 0.5) / size, (y + 0.5) / size);
    const glm::vec2 got = lut[y * size + x];
    EXPECT_NEAR(got.x, expected.x, 0.02 * expected.x + 1e-3) << "A at x " << x << " y " << y;
    EXPECT_NEAR(got.y, expected.y, 0.02 * expected.y + 1e-3) << "B at x " << x << " y " << y;
    EXPECT_NEAR(got.x + got.y, expected.x + expected.y, 0.015 * (expected.x + expected.y)) << "x " << x << " y " << y;
  }
}

// Spherical harmonics keep only the low frequencies of the irradiance, which for a clamped-cosine
// convolution is nearly all of it (Ramamoorthi and Hanrahan 2001): against the integral itself.
TEST(Environment, ShIrradianceMatchesBruteForceCosineConvolution) {
  const glm::vec3 sun = glm::normalize(glm::vec3(1, 1, -1));
  auto radiance = [&](glm::vec3 d) {
    const float sky = d.y > 0 ? 1.0f : 0.1f;
    const float lobe = 3 * std::pow(std::max(0.0f, glm::dot(d, sun)), 4.0f);
    return glm::vec3(sky + lobe, sky + 0.5f * lobe, 0.2f + sky);
  };
  const int width = 512, height = 256;
  const std::vector<float> rgb = equirect(width, height, radiance);
  const scene::Environment env = scene::prepare_environment("test", width, height, rgb, 16, 5);
  std::vector<glm::vec3> normals = {{0, 1, 0},  {0, -1, 0}, {1, 0, 0}, {-1, 0, 0},         {0, 0, 1},
                                    {0, 0, -1}, sun,        -sun,      {0.3f, -0.2f, 0.9f}};
  std::vector<glm::dvec3> expected;
  double brightest = 0;
  for (glm::vec3& n : normals) {
    n = glm::normalize(n);
    glm::dvec3 sum(0.0);
    for (int y = 0; y < height; ++y) {
      const double solid_angle = (std::cos(y * kPi / height) - std::cos((y + 1) * kPi / height)) * 2 * kPi / width;
      for (int x = 0; x < width; ++x) {
        const glm::vec3 d = scene::equirect_direction((x + 0.5f) / width, (y + 0.5f) / height);
        const float* p = rgb.data() + (std::size_t(y) * width + x) * 3;
        sum += glm::dvec3(p[0], p[1], p[2]) * double(std::max(0.0f, glm::dot(n, d))) * solid_angle / kPi;
      }
    }
    expected.push_back(sum);
    brightest = std::max({brightest, sum.r, sum.g, sum.b});
  }
  // Band 2 leaves out a few % of the sharp lobe's irradiance: 3 % of the value, and where that
  // is small (facing away from the lobe) 1 % of the brightest normal's.
  for (std::size_t i = 0; i < normals.size(); ++i) {
    const glm::vec3 got = scene::diffuse_irradiance(env, normals[i]);
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(got[c], expected[i][c], std::max(0.03 * expected[i][c], 0.01 * brightest))
          << "channel " << c << " normal " << normals[i].x << " " << normals[i].y << " " << normals[i].z;
  }
}

// The OpenGL ES 3.1 spec's cube map face table, entry by entry, and back.
TEST(Environment, CubeFaceTableFollowsTheGlSpecAndRoundTrips) {
  struct Case {
    glm::vec3 d;
    int face;
    float sc, tc, ma;
  };
  const glm::vec3 p(0.25f, 0.5f, 0.125f);  // the two minor components of each case, by name
  const Case cases[] = {
      {{1, p.y, p.z}, 0, -p.z, -p.y, 1}, {{-1, p.y, p.z}, 1, p.z, -p.y, 1}, {{p.x, 1, p.z}, 2, p.x, p.z, 1},
      {{p.x, -1, p.z}, 3, p.x, -p.z, 1}, {{p.x, p.y, 1}, 4, p.x, -p.y, 1},  {{p.x, p.y, -1}, 5, -p.x, -p.y, 1},
  };
  for (const Case& c : cases) {
    for (const float scale : {1.0f, 3.0f}) {
      const scene::CubeCoord coord = scene::cube_coord(c.d * scale);
      EXPECT_EQ(coord.face, c.face) << kAxisNames[c.face];
      EXPECT_NEAR(coord.s, (c.sc / c.ma + 1) / 2, 1e-6f) << kAxisNames[c.face];
      EXPECT_NEAR(coord.t, (c.tc / c.ma + 1) / 2, 1e-6f) << kAxisNames[c.face];
    }
  }
  for (int face = 0; face < 6; ++face) {
    const glm::vec3 centre = scene::cube_direction(face, 0.5f, 0.5f);
    EXPECT_NEAR(glm::distance(centre, kAxes[face]), 0.0f, 1e-6f) << kAxisNames[face];
  }
  for (const glm::vec3& d : directions(2000)) {
    const scene::CubeCoord coord = scene::cube_coord(d);
    ASSERT_GE(coord.face, 0);
    ASSERT_LT(coord.face, 6);
    EXPECT_GE(coord.s, 0.0f);
    EXPECT_LE(coord.s, 1.0f);
    EXPECT_GE(coord.t, 0.0f);
    EXPECT_LE(coord.t, 1.0f);
    EXPECT_NEAR(glm::distance(scene::cube_direction(coord.face, coord.s, coord.t), d), 0.0f, 1e-5f);
  }
  for (int face = 0; face < 6; ++face)
    for (float s = 0.05f; s < 1; s += 0.1f)
      for (float t = 0.05f; t < 1; t += 0.1f) {
        const scene::CubeCoord coord = scene::cube_coord(scene::cube_direction(face, s, t));
        EXPECT_EQ(coord.face, face);
        EXPECT_NEAR(coord.s, s, 1e-5f);
        EXPECT_NEAR(coord.t, t, 1e-5f);
      }
}

TEST(Environment, EquirectMappingFollowsTheDocumentedConvention) {
  const std::pair<glm::vec2, glm::vec3> cases[] = {
      {{0.5f, 0.5f}, {0, 0, -1}},                              // the image's centre looks towards -Z
      {{0.75f, 0.5f}, {1, 0, 0}},                              // a quarter to its right, +X
      {{0.25f, 0.5f}, {-1, 0, 0}}, {{0.0f, 0.5f}, {0, 0, 1}},  // the left and right edges, +Z
      {{1.0f, 0.5f}, {0, 0, 1}},   {{0.3f, 0.0f}, {0, 1, 0}},  // the top row is up
      {{0.3f, 1.0f}, {0, -1, 0}},
  };
  for (const auto& [uv, d] : cases)
    EXPECT_NEAR(glm::distance(scene::equirect_direction(uv.x, uv.y), d), 0.0f, 1e-6f) << uv.x << " " << uv.y;
  for (const glm::vec3& d : directions(500)) {
    const glm::vec2 uv = scene::equirect_uv(d);
    EXPECT_NEAR(glm::distance(scene::equirect_direction(uv.x, uv.y), d), 0.0f, 1e-5f);
  }
}

// A 2048 x 1024 image with a small, very bright sun: the time it takes is printed (not asserted);
// every level keeps the image's mean radiance (GGX's lobe around r is a zonal kernel, so the
// convolution preserves the integral) and the sun still shows where it is, up to roughness 0.6
// (rougher, the lobe gathers so much sky that straight up outshines it).
TEST(Environment, PrefilteringALargeImageKeepsItsMeanRadiance) {
  const int width = 2048, height = 1024;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> noise(0.0f, 0.3f);
  std::vector<float> rgb(std::size_t(width) * height * 3);
  const int sun_x = 1536, sun_y = 341;  // u = 0.75: +X, 30 degrees above the horizon
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      float value = (y < height / 2 ? 1.0f : 0.2f) + noise(rng);
      if (std::abs(x - sun_x) < 3 && std::abs(y - sun_y) < 3) value = 5000;
      for (int c = 0; c < 3; ++c) rgb[(std::size_t(y) * width + x) * 3 + c] = value;
    }
  double sum = 0, weights = 0;
  for (int y = 0; y < height; ++y) {
    const double weight = std::sin((y + 0.5) / height * kPi);
    for (int x = 0; x < width; ++x) sum += weight * rgb[(std::size_t(y) * width + x) * 3], weights += weight;
  }
  const double mean = sum / weights;
  const auto start = std::chrono::steady_clock::now();
  const scene::Environment env = scene::prepare_environment("large", width, height, rgb);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("prepare_environment of a %dx%d image (face %d, %d levels): %.3f s on %u threads\n", width, height, env.face_size,
              env.levels(), seconds, std::thread::hardware_concurrency());
  ASSERT_EQ(env.face_size, 128);
  ASSERT_EQ(env.levels(), 6);
  EXPECT_NEAR(env.irradiance_sh[0].r * 0.282095, mean, 0.002 * mean);
  for (int l = 0; l < env.levels(); ++l) EXPECT_NEAR(level_mean(env, l).r, mean, 0.02 * mean) << "level " << l;
  const glm::vec3 towards_sun = scene::equirect_direction((sun_x + 0.5f) / width, (sun_y + 0.5f) / height);
  for (const float roughness : {0.0f, 0.2f, 0.4f, 0.6f}) {
    const float at_sun = scene::sample_specular(env, towards_sun, roughness).r;
    for (const glm::vec3& d : directions(100)) {
      if (glm::dot(d, towards_sun) > 0.9f) continue;
      EXPECT_LT(scene::sample_specular(env, d, roughness).r, at_sun) << "roughness " << roughness;
    }
  }
}

// The studio by spec (an item naming none, or builtin:studio) is the process's one studio, prepared
// by whoever asks first (the loader's thread), so the renderer only uploads it.
TEST(Environment, TheStudioBySpecIsTheRenderersOwn) {
  for (const std::string spec : {"", "builtin:studio"}) {
    std::shared_ptr<const scene::Environment> out = std::make_shared<const scene::Environment>();
    std::string error;
    ASSERT_TRUE(scene::load_environment_spec(spec, out, error)) << error;
    EXPECT_EQ(out, nullptr) << spec;
  }
  std::shared_ptr<const scene::Environment> out;
  std::string error;
  EXPECT_FALSE(scene::load_environment_spec("builtin:sunset", out, error));
  EXPECT_NE(error.find("builtin:sunset: no such built-in environment (expected builtin:studio)"), std::string::npos) << error;
}

TEST(Environment, StudioIsNeutralBrighterAboveThanBelow) {
  const auto start = std::chrono::steady_clock::now();
  const scene::Environment& studio = scene::studio_environment();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("studio_environment prepared in %.3f s\n", seconds);
  EXPECT_EQ(&scene::studio_environment(), &studio);  // prepared once
  EXPECT_EQ(studio.name, "builtin:studio");
  const glm::vec3 up = scene::diffuse_irradiance(studio, {0, 1, 0}), down = scene::diffuse_irradiance(studio, {0, -1, 0});
  std::printf("studio: white diffuse facing up %.3f, down %.3f; mean radiance %.3f\n", up.r, down.r,
              studio.irradiance_sh[0].r * 0.282095);
  EXPECT_GT(up.r, down.r);
  EXPECT_GT(up.r, 0.72f);
  EXPECT_LT(up.r, 0.88f);
  EXPECT_GT(down.r, 0.30f);
  EXPECT_LT(down.r, 0.40f);
  const float mean = studio.irradiance_sh[0].r * 0.282095f;
  EXPECT_GT(mean, 0.5f);
  EXPECT_LT(mean, 0.7f);
  for (const glm::vec3& d : directions(100)) {
    const glm::vec3 diffuse = scene::diffuse_irradiance(studio, d);
    ASSERT_TRUE(std::isfinite(diffuse.r) && diffuse.r > 0);
    EXPECT_NEAR(diffuse.g, diffuse.r, 0.01f * diffuse.r);
    EXPECT_NEAR(diffuse.b, diffuse.r, 0.01f * diffuse.r);
    for (const float roughness : {0.0f, 0.5f, 1.0f}) {
      const glm::vec3 specular = scene::sample_specular(studio, d, roughness);
      ASSERT_TRUE(std::isfinite(specular.r) && specular.r > 0);
      EXPECT_NEAR(specular.g, specular.r, 0.01f * specular.r);
      EXPECT_NEAR(specular.b, specular.r, 0.01f * specular.r);
    }
  }
}

// Files: a folder of their own per test, removed after it.
class EnvironmentFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("environment-test-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, int width, int height, int channels, const std::vector<float>& pixels,
                    OIIO::TypeDesc format = OIIO::TypeDesc::FLOAT) {
    const std::string path = (dir_ / name).string();
    auto output = OIIO::ImageOutput::create(path);
    EXPECT_TRUE(output) << name;
    if (!output) return path;
    EXPECT_TRUE(output->open(path, OIIO::ImageSpec(width, height, channels, format))) << output->geterror();
    EXPECT_TRUE(output->write_image(OIIO::TypeDesc::FLOAT, pixels.data())) << output->geterror();
    output->close();
    return path;
  }

  std::string write_bytes(const std::string& name, const std::string& bytes) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  // A dim image, bright in pixels [x0, x1) x [y0, y1).
  static std::vector<float> patch(int width, int height, int x0, int x1, int y0, int y1) {
    std::vector<float> rgb(std::size_t(width) * height * 3, 0.05f);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x)
        for (int c = 0; c < 3; ++c) rgb[(std::size_t(y) * width + x) * 3 + c] = 8.0f;
    return rgb;
  }

  std::string refused(const std::string& path) {
    scene::Environment env;
    env.name = "untouched";
    std::string error;
    EXPECT_FALSE(scene::load_environment(path, env, error)) << path;
    EXPECT_EQ(env.name, "untouched");
    return error;
  }

  fs::path dir_;
};

// Where a bright region of the image is, the side it lights: each direction of the convention
// (the centre -Z, a quarter right +X, the top +Y), in an EXR and in a Radiance HDR file.
TEST_F(EnvironmentFile, ABrightRegionLightsTheSideTheConventionNames) {
  const int width = 64, height = 32;
  struct Region {
    int x0, x1, y0, y1;
    int axis;  // index into kAxes
  };
  const Region regions[] = {
      {28, 36, 12, 20, 5},                    // the centre: -Z
      {44, 52, 12, 20, 0},                    // a quarter of the width right of it: +X
      {12, 20, 12, 20, 1},                    // a quarter left: -X
      {0, 4, 12, 20, 4},                      // the edges: +Z
      {60, 64, 12, 20, 4}, {0, 64, 0, 6, 2},  // the top rows: +Y
      {0, 64, 26, 32, 3},                     // the bottom rows: -Y
  };
  for (const char* extension : {".exr", ".hdr"}) {
    for (const Region& r : regions) {
      const std::string path =
          write(std::string("region") + extension, width, height, 3, patch(width, height, r.x0, r.x1, r.y0, r.y1));
      scene::Environment env;
      std::string error;
      ASSERT_TRUE(scene::load_environment(path, env, error)) << error;
      EXPECT_EQ(env.name, path);
      int brightest = 0, brightest_specular = 0;
      for (int a = 1; a < 6; ++a) {
        if (scene::diffuse_irradiance(env, kAxes[a]).g > scene::diffuse_irradiance(env, kAxes[brightest]).g) brightest = a;
        if (scene::sample_specular(env, kAxes[a], 0).g > scene::sample_specular(env, kAxes[brightest_specular], 0).g)
          brightest_specular = a;
      }
      EXPECT_STREQ(kAxisNames[brightest], kAxisNames[r.axis]) << extension << " region x " << r.x0 << " y " << r.y0;
      EXPECT_STREQ(kAxisNames[brightest_specular], kAxisNames[r.axis]) << extension << " region x " << r.x0 << " y " << r.y0;
    }
  }
}

// The quadrant above the horizon and right of the centre: +X and +Y, neither +Z nor -Z more than
// the other (it spans both).
TEST_F(EnvironmentFile, TheUpperRightQuadrantLightsUpAndPlusX) {
  const int width = 64, height = 32;
  const std::string path = write("quadrant.exr", width, height, 4, [&] {
    std::vector<float> rgba;
    const std::vector<float> rgb = patch(width, height, 32, 64, 0, 16);
    for (std::size_t i = 0; i < rgb.size(); i += 3) rgba.insert(rgba.end(), {rgb[i], rgb[i + 1], rgb[i + 2], 1.0f});
    return rgba;
  }());
  scene::Environment env;
  std::string error;
  ASSERT_TRUE(scene::load_environment(path, env, error)) << error;
  auto at = [&](int axis) { return scene::diffuse_irradiance(env, kAxes[axis]).r; };
  EXPECT_GT(at(0), 3 * at(1));
  EXPECT_GT(at(2), 3 * at(3));
  EXPECT_NEAR(at(4), at(5), 0.02f * at(4));
}

// 8-bit pixels are sRGB-encoded: 128 is 0.2158 linear, not 0.5; float pixels are linear.
TEST_F(EnvironmentFile, EightBitPixelsAreDecodedFromSrgbAndFloatPixelsAreLinear) {
  const std::string path = write("grey.png", 64, 32, 3, std::vector<float>(64 * 32 * 3, 128 / 255.0f), OIIO::TypeDesc::UINT8);
  scene::Environment env;
  std::string error;
  ASSERT_TRUE(scene::load_environment(path, env, error)) << error;
  const float linear = std::pow((128 / 255.0f + 0.055f) / 1.055f, 2.4f);
  EXPECT_NEAR(scene::diffuse_irradiance(env, {0, 1, 0}).g, linear, 0.005f * linear);
  EXPECT_NEAR(scene::sample_specular(env, {1, 0, 0}, 0).g, linear, 0.005f * linear);
  // Radiance HDR's pixels are floating point: linear as they are.
  const std::string hdr = write("grey.hdr", 64, 32, 3, std::vector<float>(64 * 32 * 3, 0.5f));
  ASSERT_TRUE(scene::load_environment(hdr, env, error)) << error;
  EXPECT_NEAR(scene::diffuse_irradiance(env, {0, 1, 0}).g, 0.5f, 0.0025f);
}

TEST_F(EnvironmentFile, RefusesWhatIsNotAFiniteEquirectangularImage) {
  const std::string fifo = (dir_ / "fifo.hdr").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(refused(fifo), fifo + ": the environment image is a FIFO, not a regular file");

  const std::string missing = (dir_ / "missing.exr").string();
  EXPECT_EQ(refused(missing), missing + ": cannot open the environment image (No such file or directory)");

  const std::string expected_image = "expected an equirectangular image OpenImageIO reads (HDR, EXR, ...)";
  const std::string empty = write_bytes("empty.hdr", "");
  EXPECT_EQ(refused(empty), empty + ": the environment image is empty; " + expected_image);

  for (const char* name : {"corrupt.hdr", "corrupt.exr", "corrupt.bin"}) {
    const std::string corrupt = write_bytes(name, "this is not an image, only some text long enough to be read");
    EXPECT_EQ(
        refused(corrupt),
        corrupt + ": the environment image cannot be decoded (corrupt, truncated or of no known format); " + expected_image);
  }

  std::vector<float> wide(64 * 48 * 3, 1.0f);
  const std::string four_three = write("four-three.exr", 64, 48, 3, wide);
  EXPECT_EQ(refused(four_three), four_three +
                                     ": the environment image is 64x48; expected an equirectangular image twice as wide as "
                                     "high (64x32, within a pixel of height)");
  // Within a pixel is accepted.
  wide.resize(64 * 33 * 3);
  scene::Environment env;
  std::string error;
  EXPECT_TRUE(scene::load_environment(write("nearly.exr", 64, 33, 3, wide), env, error)) << error;

  std::vector<float> nan(64 * 32 * 3, 1.0f);
  nan[(3 * 64 + 5) * 3 + 1] = std::numeric_limits<float>::quiet_NaN();
  const std::string nan_path = write("nan.exr", 64, 32, 3, nan);
  EXPECT_EQ(refused(nan_path), nan_path + ": pixel (5, 3) channel G is NaN; expected finite, non-negative linear radiance");

  std::vector<float> infinite(64 * 32 * 3, 1.0f);
  infinite[(31 * 64 + 63) * 3] = std::numeric_limits<float>::infinity();
  const std::string infinite_path = write("infinite.exr", 64, 32, 3, infinite);
  EXPECT_EQ(refused(infinite_path),
            infinite_path + ": pixel (63, 31) channel R is infinite; expected finite, non-negative linear radiance");

  std::vector<float> negative(64 * 32 * 3, 1.0f);
  negative[(2 * 64 + 7) * 3 + 2] = -0.5f;
  const std::string negative_path = write("negative.exr", 64, 32, 3, negative);
  EXPECT_EQ(refused(negative_path),
            negative_path + ": pixel (7, 2) channel B is -0.5; expected finite, non-negative linear radiance");

  const std::string grey = write("grey.exr", 64, 32, 1, std::vector<float>(64 * 32, 1.0f));
  EXPECT_EQ(refused(grey), grey + ": the environment image has 1 channel(s); expected RGB or RGBA");
}

// Sizes are refused from the header alone: these files have no pixels at all, so getting as far as
// decoding would fail differently.
TEST_F(EnvironmentFile, RefusesTooLargeAnImageBeforeDecodingIt) {
  auto header_only = [&](const std::string& name, int width, int height) {
    return write_bytes(
        name, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n");
  };
  const std::string too_wide = header_only("too-wide.hdr", 32768, 16384);
  EXPECT_EQ(refused(too_wide), too_wide + ": the environment image is 32768x16384; expected at most 16384 pixels wide");
  const std::string over_budget = header_only("over-budget.hdr", 16384, 8192);
  EXPECT_EQ(refused(over_budget), over_budget +
                                      ": the environment image is 16384x8192, 1.5 GiB decoded as RGB floats; expected at "
                                      "most 512.0 MiB");
  const std::string truncated = header_only("truncated.hdr", 64, 32);
  EXPECT_EQ(refused(truncated), truncated +
                                    ": the environment image's pixels cannot be decoded (corrupt or truncated); expected an "
                                    "equirectangular image OpenImageIO reads (HDR, EXR, ...)");
}

}  // namespace
