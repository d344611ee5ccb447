#include "aoref/reference.h"

#include "ssao/sampling.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <numbers>
#include <thread>

namespace aoref {
namespace {

double radical_inverse(uint32_t i, uint32_t base) {
  double result = 0.0, scale = 1.0 / base;
  for (; i > 0; i /= base, scale /= base) result += (i % base) * scale;
  return result;
}

double wrap(double u) {
  return u - std::floor(u);
}

// An orthonormal basis with `n` as its third axis (Duff et al. 2017: no branch on a chosen axis).
void basis(const glm::dvec3& n, glm::dvec3& t, glm::dvec3& b) {
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z);
  const double c = n.x * n.y * a;
  t = glm::dvec3(1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x);
  b = glm::dvec3(c, sign + n.y * n.y * a, -n.y);
}

// Low-discrepancy points shared by every pixel: Hammersley ((i + 0.5) / N, radical inverses in
// bases 2 and 3). Each pixel shifts them by its own random offset modulo 1 (Cranley-Patterson), which
// keeps the estimate unbiased and the pixels' errors independent while stratifying each pixel.
std::vector<glm::dvec3> hammersley(int n) {
  std::vector<glm::dvec3> points(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i)
    points[static_cast<size_t>(i)] = {(i + 0.5) / n, radical_inverse(static_cast<uint32_t>(i), 2),
                                      radical_inverse(static_cast<uint32_t>(i), 3)};
  return points;
}

struct Job {
  const RayScene& scene;
  const View& view;
  const ReferenceSettings& settings;
  double near_field_radius;
  std::vector<glm::dvec3> points;
  ReferenceResult& out;
};

// Object pixels with a normal to trace from. A zero normal (never written by a validated dump, but
// possible in a view filled in memory) leaves the pixel at 0, uncounted, rather than tracing NaNs.
bool usable(const View& view, size_t pixel) {
  if (!view.is_object(pixel)) return false;
  const glm::dvec3 n(view.normal.at(pixel, 0), view.normal.at(pixel, 1), view.normal.at(pixel, 2));
  const glm::dvec3 p(view.position.at(pixel, 0), view.position.at(pixel, 1), view.position.at(pixel, 2));
  return glm::length(n) > 0.5 && std::isfinite(p.x + p.y + p.z);
}

double binomial_error(double p, int n) {
  return std::sqrt(std::max(0.0, p * (1.0 - p)) / n);
}

void trace_pixel(const Job& job, size_t pixel) {
  const View& view = job.view;
  const glm::dvec3 p(view.position.at(pixel, 0), view.position.at(pixel, 1), view.position.at(pixel, 2));
  glm::dvec3 n(view.normal.at(pixel, 0), view.normal.at(pixel, 1), view.normal.at(pixel, 2));
  // The dump stores normals as half floats; renormalise so the basis is orthonormal.
  n = glm::normalize(n);
  ssao::Random random(job.settings.seed * 0x9E3779B97F4A7C15ull + pixel);
  const glm::dvec3 shift(random.uniform(), random.uniform(), random.uniform());
  const int rays = job.settings.rays;

  if (job.settings.reference == Reference::near_field) {
    glm::dvec3 t, b;
    basis(n, t, b);
    const glm::dvec3 origin = p + surface_epsilon(job.scene.scene_radius(), p) * n;
    int hits = 0;
    for (const glm::dvec3& point : job.points) {
      // Malley's method: uniform on the unit disk, lifted to the hemisphere, is cosine-weighted.
      const double u = wrap(point.x + shift.x), v = wrap(point.y + shift.y);
      const double r = std::sqrt(u), phi = 2.0 * std::numbers::pi * v;
      const glm::dvec3 direction = r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0, 1.0 - u)) * n;
      hits += job.scene.occluded(origin, direction, 0.0, job.near_field_radius) ? 1 : 0;
    }
    const double fraction = static_cast<double>(hits) / rays;
    job.out.ao.at(pixel) = job.out.per_radius[0].at(pixel) = static_cast<float>(fraction);
    job.out.standard_error.at(pixel) = static_cast<float>(binomial_error(fraction, rays));
    return;
  }

  // Sphere: the same shifted points for every radius, scaled, as the player scales one kernel; this
  // correlates the radii's estimates and so keeps the max from favouring whichever is noisiest.
  double best = -1.0;
  for (size_t k = 0; k < view.radii.size(); ++k) {
    const double radius = view.radii[k];
    int hidden = 0;
    for (const glm::dvec3& point : job.points) {
      const glm::dvec2 xi(wrap(point.x + shift.x) * 2.0 - 1.0, wrap(point.y + shift.y) * 2.0 - 1.0);
      const double r = ssao::shell_radius(wrap(point.z + shift.z), ssao::kShellMin * radius, radius);
      const glm::dvec3 q = p + r * ssao::sphere_point(xi);
      // Blocked anywhere on the segment from the eye to the point. No epsilon: the point is at least
      // 0.8 R from the surface it was drawn around, and lies on some other surface with probability 0.
      hidden += job.scene.occluded(job.view.eye, q - job.view.eye, 0.0, 1.0) ? 1 : 0;
    }
    const double fraction = static_cast<double>(hidden) / rays;
    job.out.per_radius[k].at(pixel) = static_cast<float>(fraction);
    if (fraction > best) best = fraction;
  }
  job.out.ao.at(pixel) = static_cast<float>(best);
  job.out.standard_error.at(pixel) = static_cast<float>(binomial_error(best, rays));
}

}  // namespace

std::string_view name(Reference reference) {
  switch (reference) {
    case Reference::near_field:
      return "near-field";
    case Reference::sphere:
      return "sphere";
  }
  return "unknown";
}

std::optional<Reference> parse_reference(std::string_view text) {
  for (Reference r : {Reference::near_field, Reference::sphere})
    if (text == name(r)) return r;
  return std::nullopt;
}

double surface_epsilon(double scene_radius, const glm::dvec3& point) {
  const double largest = std::max({std::abs(point.x), std::abs(point.y), std::abs(point.z)});
  return 1e-5 * scene_radius + 1e-6 * largest;
}

bool compute_reference(const RayScene& scene, const View& view, const ReferenceSettings& settings, ReferenceResult& out,
                       std::string& error) {
  if (settings.rays < 1 || settings.rays > 1 << 20) {
    error = "rays: expected 1 to " + std::to_string(1 << 20) + ", found " + std::to_string(settings.rays);
    return false;
  }
  if (!std::isfinite(settings.radius) || settings.radius < 0.0) {
    error = "radius: expected a positive finite number (or 0 for the view's largest radius), found " +
            std::to_string(settings.radius);
    return false;
  }
  if (view.position.channels < 4 || view.normal.channels < 3 || !view.position.same_size(view.normal) ||
      view.position.width <= 0 || view.position.height <= 0) {
    error = "view: expected position (4 channels) and normal (3 or 4 channels) images of one non-empty size, found " +
            std::to_string(view.position.width) + "x" + std::to_string(view.position.height) + "x" +
            std::to_string(view.position.channels) + " and " + std::to_string(view.normal.width) + "x" +
            std::to_string(view.normal.height) + "x" + std::to_string(view.normal.channels);
    return false;
  }
  if (view.radii.empty() ||
      std::any_of(view.radii.begin(), view.radii.end(), [](double r) { return !(r > 0.0) || !std::isfinite(r); })) {
    error = "view.radii: expected at least one positive finite radius";
    return false;
  }
  if (scene.triangle_count() == 0) {
    error = "scene: expected a built RayScene with triangles, found none";
    return false;
  }
  for (int c = 0; c < 3; ++c) {
    if (!std::isfinite(view.eye[c]) && settings.reference == Reference::sphere) {
      error = "view.eye: expected finite coordinates";
      return false;
    }
  }

  const int width = view.width(), height = view.height();
  ReferenceResult result;
  result.ao = Image(width, height, 1);
  result.standard_error = Image(width, height, 1);
  result.per_radius.assign(settings.reference == Reference::sphere ? view.radii.size() : 1, Image(width, height, 1));
  const double near_field_radius = settings.radius > 0.0 ? settings.radius : view.radii.front();
  Job job{scene, view, settings, near_field_radius, hammersley(settings.rays), result};

  const unsigned hardware = std::max(1u, std::thread::hardware_concurrency());
  const int threads = std::clamp(settings.threads > 0 ? settings.threads : static_cast<int>(hardware), 1, height);
  std::atomic<int> next_row{0}, rows_done{0};
  std::mutex mutex;
  std::condition_variable finished_cv;
  int finished = 0;
  std::vector<std::thread> workers;
  for (int t = 0; t < threads; ++t) {
    workers.emplace_back([&] {
      for (int y = next_row++; y < height; y = next_row++) {
        for (int x = 0; x < width; ++x) {
          const size_t pixel = static_cast<size_t>(y) * static_cast<size_t>(width) + static_cast<size_t>(x);
          if (usable(view, pixel)) trace_pixel(job, pixel);
        }
        ++rows_done;
      }
      std::lock_guard lock(mutex);
      ++finished;
      finished_cv.notify_one();
    });
  }
  {
    std::unique_lock lock(mutex);
    while (!finished_cv.wait_for(lock, std::chrono::milliseconds(100), [&] { return finished == threads; }))
      if (settings.progress) settings.progress(rows_done.load(), height);
  }
  for (std::thread& worker : workers) worker.join();
  if (settings.progress) settings.progress(height, height);

  double sum = 0.0;
  for (size_t i = 0; i < result.ao.pixel_count(); ++i) {
    if (!usable(view, i)) continue;
    const double se = result.standard_error.at(i);
    ++result.object_pixels;
    sum += se;
    result.max_standard_error = std::max(result.max_standard_error, se);
  }
  result.mean_standard_error = result.object_pixels ? sum / static_cast<double>(result.object_pixels) : 0.0;
  const uint64_t per_pixel =
      static_cast<uint64_t>(settings.rays) * (settings.reference == Reference::sphere ? view.radii.size() : 1);
  result.rays_traced = per_pixel * result.object_pixels;
  out = std::move(result);
  return true;
}

}  // namespace aoref
