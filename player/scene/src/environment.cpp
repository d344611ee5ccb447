#include "scene/environment.h"

#include "base/image_codec.h"
#include "base/read_file.h"
#include "environment_cache.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <utility>

namespace scene {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr float kPiF = static_cast<float>(kPi);

// Runs f(0) .. f(count - 1) on every core. Each index writes only its own output, and sums are
// reduced afterwards in index order, so the result does not depend on the number of threads.
template <class F>
void parallel_for(int count, const F& f) {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const int workers = static_cast<int>(std::min<unsigned>(cores, static_cast<unsigned>(std::max(count, 1))));
  std::atomic<int> next{0};
  auto run = [&] {
    for (int i = next.fetch_add(1); i < count; i = next.fetch_add(1)) f(i);
  };
  std::vector<std::thread> threads;
  for (int w = 1; w < workers; ++w) {
    try {
      threads.emplace_back(run);
    } catch (const std::system_error&) {
      break;  // no thread to be had: the ones there are (this one at least) do the rest
    }
  }
  run();
  for (std::thread& thread : threads) thread.join();
}

// An image of RGB floats, row 0 at the top.
struct Equirect {
  int width = 0, height = 0;
  const float* rgb = nullptr;

  glm::vec3 texel(int x, int y) const {
    const float* p = rgb + (static_cast<std::size_t>(y) * width + x) * 3;
    return {p[0], p[1], p[2]};
  }
  // Bilinear, wrapping around in longitude and clamped at the poles' rows.
  glm::vec3 sample(glm::vec2 uv) const {
    const float fx = uv.x * width - 0.5f, fy = std::clamp(uv.y * height - 0.5f, 0.0f, float(height - 1));
    const float x0f = std::floor(fx), y0f = std::floor(fy);
    const float ax = fx - x0f, ay = fy - y0f;
    const int x0 = ((static_cast<int>(x0f) % width) + width) % width, x1 = (x0 + 1) % width;
    const int y0 = static_cast<int>(y0f), y1 = std::min(y0 + 1, height - 1);
    return glm::mix(glm::mix(texel(x0, y0), texel(x1, y0), ax), glm::mix(texel(x0, y1), texel(x1, y1), ax), ay);
  }
};

// One level of a cube map in Environment::specular's layout.
struct CubeLevel {
  int size = 0;
  const float* rgb = nullptr;

  glm::vec3 texel(int face, int x, int y) const {
    const float* p = rgb + ((static_cast<std::size_t>(face) * size + y) * size + x) * 3;
    return {p[0], p[1], p[2]};
  }
  // Bilinear within the face, clamped at its edges: textureLod's filtering but for the seamless
  // blend across edges, which the GPU does and this does not (a fraction of a texel at the edges).
  glm::vec3 sample(const CubeCoord& c) const {
    const float fx = std::clamp(c.s * size - 0.5f, 0.0f, float(size - 1));
    const float fy = std::clamp(c.t * size - 0.5f, 0.0f, float(size - 1));
    const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
    const int x1 = std::min(x0 + 1, size - 1), y1 = std::min(y0 + 1, size - 1);
    const float ax = fx - float(x0), ay = fy - float(y0);
    return glm::mix(glm::mix(texel(c.face, x0, y0), texel(c.face, x1, y0), ax),
                    glm::mix(texel(c.face, x0, y1), texel(c.face, x1, y1), ax), ay);
  }
};

glm::vec3 sample_levels(const std::vector<std::vector<float>>& levels, int size0, const CubeCoord& c, float lod) {
  const int last = static_cast<int>(levels.size()) - 1;
  lod = std::clamp(lod, 0.0f, float(last));
  const int l0 = static_cast<int>(lod), l1 = std::min(l0 + 1, last);
  const glm::vec3 a = CubeLevel{size0 >> l0, levels[l0].data()}.sample(c);
  if (l1 == l0) return a;
  return glm::mix(a, CubeLevel{size0 >> l1, levels[l1].data()}.sample(c), lod - float(l0));
}

// The radiance of the clamped cosine's projection over pi per band (Ramamoorthi and Hanrahan 2001).
constexpr std::array<double, 9> kBandFactor = {1.0, 2.0 / 3, 2.0 / 3, 2.0 / 3, 0.25, 0.25, 0.25, 0.25, 0.25};

// The radiance's projection on the basis. Each pixel is taken as constant over its own patch of
// the sphere, and the basis is integrated over that patch exactly: every Y_i is a product of a
// function of theta and one of phi, whose integrals over the pixel's row and column have closed
// forms. So a uniform image projects exactly however few its rows, where sampling each pixel at
// its centre would be off by about (1 / height)^2 in band 2.
std::array<glm::vec3, 9> project_sh(const Equirect& image) {
  // Over a column [phi0, phi1] (phi as in equirect_direction): 1, sin, cos, sin^2, cos^2, sin cos.
  struct Column {
    double one, s, c, ss, cc, sc;
  };
  std::vector<Column> columns(static_cast<std::size_t>(image.width));
  auto phi_of = [&](int x) { return (double(x) / image.width - 0.5) * 2 * kPi; };
  for (int x = 0; x < image.width; ++x) {
    const double a = phi_of(x), b = phi_of(x + 1);
    columns[x] = {b - a,
                  std::cos(a) - std::cos(b),
                  std::sin(b) - std::sin(a),
                  (b - a) / 2 - (std::sin(2 * b) - std::sin(2 * a)) / 4,
                  (b - a) / 2 + (std::sin(2 * b) - std::sin(2 * a)) / 4,
                  (std::sin(b) * std::sin(b) - std::sin(a) * std::sin(a)) / 2};
  }
  std::vector<std::array<glm::dvec3, 9>> rows(static_cast<std::size_t>(image.height));
  parallel_for(image.height, [&](int y) {
    // Over the row [theta0, theta1], with the solid angle's sin(theta): sin, cos sin, sin^2,
    // sin^2 cos, sin^3, cos^2 sin.
    const double a = double(y) / image.height * kPi, b = double(y + 1) / image.height * kPi;
    const double ca = std::cos(a), cb = std::cos(b), sa = std::sin(a), sb = std::sin(b);
    const double t_s = ca - cb, t_cs = (sb * sb - sa * sa) / 2, t_ss = (b - a) / 2 - (std::sin(2 * b) - std::sin(2 * a)) / 4;
    const double t_ssc = (sb * sb * sb - sa * sa * sa) / 3, t_sss = (ca - cb) - (ca * ca * ca - cb * cb * cb) / 3;
    const double t_ccs = (ca * ca * ca - cb * cb * cb) / 3;
    std::array<glm::dvec3, 9> sum{};
    for (int x = 0; x < image.width; ++x) {
      // d = (sin theta sin phi, cos theta, -sin theta cos phi); the constants are sh_basis's.
      const Column& p = columns[x];
      const double weight[9] = {0.282095 * t_s * p.one,
                                0.488603 * t_cs * p.one,
                                0.488603 * -t_ss * p.c,
                                0.488603 * t_ss * p.s,
                                1.092548 * t_ssc * p.s,
                                1.092548 * -t_ssc * p.c,
                                0.315392 * (3 * t_sss * p.cc - t_s * p.one),
                                1.092548 * -t_sss * p.sc,
                                0.546274 * (t_sss * p.ss - t_ccs * p.one)};
      const glm::dvec3 radiance(image.texel(x, y));
      for (int i = 0; i < 9; ++i) sum[i] += radiance * weight[i];
    }
    rows[y] = sum;
  });
  std::array<glm::dvec3, 9> total{};
  for (const auto& row : rows)
    for (int i = 0; i < 9; ++i) total[i] += row[i];
  std::array<glm::vec3, 9> out{};
  for (int i = 0; i < 9; ++i) out[i] = glm::vec3(total[i] * kBandFactor[i]);
  return out;
}

// The cube at full size. A texel of a 128 face spans about four pixels of a 2048-wide image, so
// each texel averages k x k bilinear reads spaced about a pixel apart: a small bright light is
// neither missed nor picked up at full strength by the one read that lands on it.
std::vector<float> cube_from_equirect(const Equirect& image, int size) {
  const int k = std::clamp((image.width + 4 * size - 1) / (4 * size), 1, 16);
  std::vector<float> out(static_cast<std::size_t>(6) * size * size * 3);
  parallel_for(6 * size, [&](int row) {
    const int face = row / size, y = row % size;
    for (int x = 0; x < size; ++x) {
      glm::vec3 sum(0.0f);
      for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i) {
          const float s = (x + (i + 0.5f) / k) / size, t = (y + (j + 0.5f) / k) / size;
          sum += image.sample(equirect_uv(cube_direction(face, s, t)));
        }
      sum /= float(k * k);
      float* p = out.data() + ((static_cast<std::size_t>(face) * size + y) * size + x) * 3;
      p[0] = sum.r;
      p[1] = sum.g;
      p[2] = sum.b;
    }
  });
  return out;
}

// Halves a cube level by averaging 2 x 2 texels.
std::vector<float> box_down(const std::vector<float>& level, int size) {
  const int half = size / 2;
  std::vector<float> out(static_cast<std::size_t>(6) * half * half * 3);
  for (int face = 0; face < 6; ++face)
    for (int y = 0; y < half; ++y)
      for (int x = 0; x < half; ++x)
        for (int c = 0; c < 3; ++c) {
          auto at = [&](int xx, int yy) { return level[((std::size_t(face) * size + yy) * size + xx) * 3 + c]; };
          out[((std::size_t(face) * half + y) * half + x) * 3 + c] =
              0.25f * (at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1));
        }
  return out;
}

glm::vec2 hammersley(uint32_t i, uint32_t count) {
  uint32_t bits = i;
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return {(float(i) + 0.5f) / float(count), float(bits) * 2.3283064365386963e-10f};
}

// A half vector around +Z distributed as GGX's D(h) (h.n): Karis 2013's ImportanceSampleGGX.
glm::vec3 sample_ggx(glm::vec2 xi, float alpha) {
  const float phi = 2 * kPiF * xi.x;
  const float cos_theta = std::sqrt((1 - xi.y) / (1 + (alpha * alpha - 1) * xi.y));
  const float sin_theta = std::sqrt(std::max(0.0f, 1 - cos_theta * cos_theta));
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

float ggx_d(float n_dot_h, float alpha) {
  const float a2 = alpha * alpha, f = (a2 - 1) * n_dot_h * n_dot_h + 1;
  return a2 / (kPiF * f * f);
}

// Height-correlated Smith's G over 4 (n.l) (n.v) (Heitz 2014; Filament's V_SmithGGXCorrelated).
float smith_visibility(float n_dot_v, float n_dot_l, float alpha) {
  const float a2 = alpha * alpha;
  const float v = n_dot_l * std::sqrt(n_dot_v * n_dot_v * (1 - a2) + a2);
  const float l = n_dot_v * std::sqrt(n_dot_l * n_dot_l * (1 - a2) + a2);
  return 0.5f / (v + l);
}

// One prefiltered level. With n = v = r the GGX lobe around r is the same for every texel, so its
// samples (direction around +Z, weight n.l, source level) are made once and turned to each texel.
// Each sample reads the source level whose texels cover the solid angle the sample stands for,
// 1 / (count pdf) (Krivanek and Colbert 2008, "Real-time shading with filtered importance
// sampling", with their bias of one level), so a bright pixel is spread over the samples that
// would each have hit or missed it: no fireflies, and few samples suffice.
std::vector<float> prefilter(const std::vector<std::vector<float>>& source, int size0, int size, float roughness, int count) {
  struct Sample {
    glm::vec3 l;
    float weight, lod;
  };
  const float alpha = roughness * roughness;
  const float texel_solid_angle = 4 * kPiF / (6.0f * float(size0) * float(size0));
  std::vector<Sample> samples;
  float total = 0;
  for (int i = 0; i < count; ++i) {
    const glm::vec3 h = sample_ggx(hammersley(uint32_t(i), uint32_t(count)), alpha);
    const glm::vec3 l = 2 * h.z * h - glm::vec3(0, 0, 1);
    if (l.z <= 0) continue;
    const float pdf = ggx_d(h.z, alpha) / 4;  // D (n.h) / (4 v.h), and n.h = v.h when n = v
    const float sample_solid_angle = 1 / (float(count) * pdf);
    samples.push_back({l, l.z, 0.5f * std::log2(sample_solid_angle / texel_solid_angle) + 1});
    total += l.z;
  }
  for (Sample& s : samples) s.weight /= total;
  std::vector<float> out(static_cast<std::size_t>(6) * size * size * 3);
  parallel_for(6 * size, [&](int row) {
    const int face = row / size, y = row % size;
    for (int x = 0; x < size; ++x) {
      const glm::vec3 n = cube_direction(face, (x + 0.5f) / size, (y + 0.5f) / size);
      const glm::vec3 up = std::abs(n.z) < 0.999f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
      const glm::vec3 tangent = glm::normalize(glm::cross(up, n)), bitangent = glm::cross(n, tangent);
      glm::vec3 sum(0.0f);
      for (const Sample& s : samples) {
        const glm::vec3 l = tangent * s.l.x + bitangent * s.l.y + n * s.l.z;
        sum += s.weight * sample_levels(source, size0, cube_coord(l), s.lod);
      }
      float* p = out.data() + ((static_cast<std::size_t>(face) * size + y) * size + x) * 3;
      p[0] = sum.r;
      p[1] = sum.g;
      p[2] = sum.b;
    }
  });
  return out;
}

float srgb_to_linear(float c) {
  return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f);
}

float smoothstep(float edge0, float edge1, float x) {
  const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
  return t * t * (3 - 2 * t);
}

// The studio's radiance towards the unit direction d.
float studio_radiance(glm::vec3 d) {
  // The surround: a floor darker than the walls, the walls darker than the ceiling, blended so
  // that no edge shows in reflections.
  float radiance = 0.36f + 0.27f * smoothstep(-0.35f, 0.6f, d.y);
  // Two soft boxes, broad enough to read as shapes on rough metal and not as points: a key high on
  // the default camera's side (+Z) and to its left, a fainter one behind the model to the right.
  auto soft_box = [&](glm::vec3 centre, float inner_degrees, float outer_degrees, float strength) {
    const float c = glm::dot(d, glm::normalize(centre));
    return strength * smoothstep(std::cos(glm::radians(outer_degrees)), std::cos(glm::radians(inner_degrees)), c);
  };
  radiance += soft_box({-0.6f, 0.9f, 0.7f}, 14, 26, 1.5f);
  radiance += soft_box({0.8f, 0.6f, -0.6f}, 12, 24, 1.0f);
  return radiance;
}

// prepare_environment()'s work when no kept copy is found: defined below it, beside it in the file.
Environment prefilter_environment(std::string name, int width, int height, const std::vector<float>& rgb, int face_size,
                                  int levels);

}  // namespace

std::array<float, 9> sh_basis(glm::vec3 n) {
  return {0.282095f,
          0.488603f * n.y,
          0.488603f * n.z,
          0.488603f * n.x,
          1.092548f * n.x * n.y,
          1.092548f * n.y * n.z,
          0.315392f * (3 * n.z * n.z - 1),
          1.092548f * n.x * n.z,
          0.546274f * (n.x * n.x - n.y * n.y)};
}

glm::vec3 diffuse_irradiance(const Environment& env, glm::vec3 normal) {
  const std::array<float, 9> y = sh_basis(glm::normalize(normal));
  glm::vec3 sum(0.0f);
  for (int i = 0; i < 9; ++i) sum += env.irradiance_sh[i] * y[i];
  return glm::max(sum, glm::vec3(0.0f));
}

glm::vec3 sample_specular(const Environment& env, glm::vec3 direction, float roughness) {
  if (env.specular.empty()) return glm::vec3(0.0f);
  const float lod = std::clamp(roughness, 0.0f, 1.0f) * float(env.levels() - 1);
  return sample_levels(env.specular, env.face_size, cube_coord(direction), lod);
}

CubeCoord cube_coord(glm::vec3 d) {
  const glm::vec3 a = glm::abs(d);
  CubeCoord c;
  float ma = 0, sc = 0, tc = 0;
  if (a.x >= a.y && a.x >= a.z) {
    c.face = d.x >= 0 ? 0 : 1;
    ma = a.x;
    sc = d.x >= 0 ? -d.z : d.z;
    tc = -d.y;
  } else if (a.y >= a.z) {
    c.face = d.y >= 0 ? 2 : 3;
    ma = a.y;
    sc = d.x;
    tc = d.y >= 0 ? d.z : -d.z;
  } else {
    c.face = d.z >= 0 ? 4 : 5;
    ma = a.z;
    sc = d.z >= 0 ? d.x : -d.x;
    tc = -d.y;
  }
  if (!(ma > 0)) return CubeCoord{};
  c.s = 0.5f * (sc / ma + 1);
  c.t = 0.5f * (tc / ma + 1);
  return c;
}

glm::vec3 cube_direction(int face, float s, float t) {
  const float sc = 2 * s - 1, tc = 2 * t - 1;
  glm::vec3 d;
  switch (face) {
    case 0:
      d = {1, -tc, -sc};
      break;
    case 1:
      d = {-1, -tc, sc};
      break;
    case 2:
      d = {sc, 1, tc};
      break;
    case 3:
      d = {sc, -1, -tc};
      break;
    case 4:
      d = {sc, -tc, 1};
      break;
    default:
      d = {-sc, -tc, -1};
      break;
  }
  return glm::normalize(d);
}

glm::vec2 equirect_uv(glm::vec3 d) {
  const float u = 0.5f + std::atan2(d.x, -d.z) / (2 * kPiF);
  const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPiF;
  return {u, v};
}

glm::vec3 equirect_direction(float u, float v) {
  const float phi = (u - 0.5f) * 2 * kPiF, theta = v * kPiF;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

Environment prepare_environment(std::string name, int width, int height, const std::vector<float>& rgb, int face_size,
                                int levels) {
  if (width <= 0 || height <= 0 || rgb.size() != std::size_t(width) * std::size_t(height) * 3)
    throw std::invalid_argument("prepare_environment: expected width x height x 3 floats");
  if (face_size <= 0 || (face_size & (face_size - 1)) != 0 || levels < 1 || levels > 31 || (face_size >> (levels - 1)) < 1)
    throw std::invalid_argument("prepare_environment: expected a power-of-two face size with at least 1 texel at the last level");
  if (std::optional<Environment> kept = detail::kept_environment(width, height, rgb, face_size, levels)) {
    kept->name = std::move(name);
    return std::move(*kept);
  }
  Environment env = prefilter_environment(std::move(name), width, height, rgb, face_size, levels);
  detail::keep_environment(width, height, rgb, env);
  return env;
}

namespace {

Environment prefilter_environment(std::string name, int width, int height, const std::vector<float>& rgb, int face_size,
                                  int levels) {
  const Equirect image{width, height, rgb.data()};
  Environment env;
  env.name = std::move(name);
  env.face_size = face_size;
  env.irradiance_sh = project_sh(image);
  // The source of the prefiltering: the cube and its box-filtered mips down to 1 x 1.
  std::vector<std::vector<float>> source{cube_from_equirect(image, face_size)};
  for (int size = face_size; size > 1; size /= 2) source.push_back(box_down(source.back(), size));
  env.specular.push_back(source[0]);
  for (int l = 1; l < levels; ++l) {
    // More samples where the texels are fewer: every level costs about the same, and the wide
    // lobes of rough levels, which gather from far apart, get the most.
    const int count = std::min(1024, 64 << l);
    env.specular.push_back(prefilter(source, face_size, face_size >> l, float(l) / float(levels - 1), count));
  }
  return env;
}

}  // namespace

Environment uniform_environment(glm::vec3 radiance, int face_size) {
  const int width = 16, height = 8;
  std::vector<float> rgb;
  rgb.reserve(width * height * 3);
  for (int i = 0; i < width * height; ++i) rgb.insert(rgb.end(), {radiance.r, radiance.g, radiance.b});
  int levels = 1;
  while (levels < 6 && (face_size >> levels) >= 1) ++levels;
  return prepare_environment("uniform", width, height, rgb, face_size, levels);
}

const Environment& studio_environment() {
  static const Environment studio = [] {
    // Smooth everywhere, so a small image carries it all.
    const int width = 512, height = 256;
    std::vector<float> rgb(std::size_t(width) * height * 3);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const float radiance = studio_radiance(equirect_direction((x + 0.5f) / width, (y + 0.5f) / height));
        float* p = rgb.data() + (std::size_t(y) * width + x) * 3;
        p[0] = p[1] = p[2] = radiance;
      }
    return prepare_environment("builtin:studio", width, height, rgb);
  }();
  return studio;
}

std::vector<glm::vec2> split_sum_lut(int size, int samples) {
  std::vector<glm::vec2> lut(static_cast<std::size_t>(std::max(size, 0)) * std::max(size, 0));
  for (int y = 0; y < size; ++y) {
    const float roughness = (y + 0.5f) / size, alpha = roughness * roughness;
    for (int x = 0; x < size; ++x) {
      const float n_dot_v = (x + 0.5f) / size;
      const glm::vec3 v(std::sqrt(1 - n_dot_v * n_dot_v), 0, n_dot_v);
      double a = 0, b = 0;
      for (int i = 0; i < samples; ++i) {
        const glm::vec3 h = sample_ggx(hammersley(uint32_t(i), uint32_t(samples)), alpha);
        const float v_dot_h = glm::dot(v, h);
        const glm::vec3 l = 2 * v_dot_h * h - v;
        if (l.z <= 0 || v_dot_h <= 0) continue;
        // f (n.l) / pdf with f = D V F and pdf = D (n.h) / (4 v.h): D cancels.
        const float g = smith_visibility(n_dot_v, l.z, alpha) * 4 * l.z * v_dot_h / h.z;
        const float fresnel = std::pow(1 - v_dot_h, 5.0f);
        a += (1 - fresnel) * g;
        b += fresnel * g;
      }
      lut[std::size_t(y) * size + x] = glm::vec2(float(a / samples), float(b / samples));
    }
  }
  return lut;
}

bool load_environment(const std::filesystem::path& file, Environment& out, std::string& error) {
  const std::string path = file.string();
  auto fail = [&](const std::string& what) {
    error = path + ": " + what;
    return false;
  };
  std::string bytes;
  if (!base::read_regular_file(path, "environment image", kEnvironmentMaxFileBytes, bytes, error)) return false;
  const std::string expected_image = "expected an equirectangular image OpenImageIO reads (HDR, EXR, ...)";
  if (bytes.empty()) return fail("the environment image is empty; " + expected_image);
  // OpenImageIO picks its reader by the name's extension, and tries each in turn when that fails;
  // every one of them reads from memory, so the file is not opened a second time.
  std::string why;
  const std::unique_ptr<base::images::Reader> input = base::images::make_reader("", why);
  if (!input) return fail(why);
  base::images::Header spec;
  // Its messages name the file as missing when no reader knows the data; ours says what it is.
  if (!input->open(path, bytes.data(), bytes.size(), spec, why))
    return fail("the environment image cannot be decoded (corrupt, truncated or of no known format); " + expected_image);
  const std::string dimensions = std::to_string(spec.width) + "x" + std::to_string(spec.height);
  if (spec.width <= 0 || spec.height <= 0 || spec.depth > 1)
    return fail("the environment image is " + dimensions + "; " + expected_image);
  if (spec.channels < 3)
    return fail("the environment image has " + std::to_string(spec.channels) + " channel(s); expected RGB or RGBA");
  if (spec.width > kEnvironmentMaxWidth)
    return fail("the environment image is " + dimensions + "; expected at most " + std::to_string(kEnvironmentMaxWidth) +
                " pixels wide");
  if (std::abs(2 * int64_t(spec.height) - int64_t(spec.width)) > 2)
    return fail("the environment image is " + dimensions + "; expected an equirectangular image twice as wide as high (" +
                std::to_string(spec.width) + "x" + std::to_string(spec.width / 2) + ", within a pixel of height)");
  const std::size_t decoded = std::size_t(spec.width) * std::size_t(spec.height) * 3 * sizeof(float);
  if (decoded > kEnvironmentDecodedBudget)
    return fail("the environment image is " + dimensions + ", " + base::byte_size_text(decoded) +
                " decoded as RGB floats; expected at most " + base::byte_size_text(kEnvironmentDecodedBudget));
  std::vector<float> rgb(decoded / sizeof(float));
  std::string messages;
  const bool read = input->read(3, rgb.data(), messages);
  if (!read || !messages.empty())
    return fail("the environment image's pixels cannot be decoded (corrupt or truncated); " + expected_image);
  if (!spec.floating)
    for (float& c : rgb) c = srgb_to_linear(c);
  static const char* const kChannel[] = {"R", "G", "B"};
  for (std::size_t i = 0; i < rgb.size(); ++i) {
    if (std::isfinite(rgb[i]) && rgb[i] >= 0) continue;
    const std::size_t pixel = i / 3;
    const std::string where = "pixel (" + std::to_string(pixel % std::size_t(spec.width)) + ", " +
                              std::to_string(pixel / std::size_t(spec.width)) + ") channel " + kChannel[i % 3];
    char number[32];
    std::snprintf(number, sizeof number, "%g", double(rgb[i]));
    const std::string value = std::isnan(rgb[i]) ? "NaN" : std::isinf(rgb[i]) ? "infinite" : number;
    return fail(where + " is " + value + "; expected finite, non-negative linear radiance");
  }
  out = prepare_environment(path, spec.width, spec.height, rgb);
  return true;
}

}  // namespace scene
