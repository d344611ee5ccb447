#include "aoref/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace aoref {
namespace {

std::string size_text(const Image& image) {
  return std::to_string(image.width) + "x" + std::to_string(image.height);
}

// Mean SSIM over object pixels with a masked, renormalised Gaussian window.
double masked_ssim(const Image& x, const Image& y, const std::vector<uint8_t>& object, const MetricsSettings& settings) {
  constexpr double c1 = (0.01 * 1.0) * (0.01 * 1.0), c2 = (0.03 * 1.0) * (0.03 * 1.0);
  const int radius = std::max(0, settings.ssim_radius);
  std::vector<double> weights(static_cast<size_t>(2 * radius + 1));
  for (int i = -radius; i <= radius; ++i)
    weights[static_cast<size_t>(i + radius)] = std::exp(-0.5 * i * i / (settings.ssim_sigma * settings.ssim_sigma));
  const int w = x.width, h = x.height;
  double total = 0.0;
  size_t count = 0;
  for (int cy = 0; cy < h; ++cy) {
    for (int cx = 0; cx < w; ++cx) {
      const size_t centre = static_cast<size_t>(cy) * static_cast<size_t>(w) + static_cast<size_t>(cx);
      if (!object[centre]) continue;
      double sw = 0.0, mx = 0.0, my = 0.0, mxx = 0.0, myy = 0.0, mxy = 0.0;
      for (int dy = -radius; dy <= radius; ++dy) {
        const int py = cy + dy;
        if (py < 0 || py >= h) continue;
        for (int dx = -radius; dx <= radius; ++dx) {
          const int px = cx + dx;
          if (px < 0 || px >= w) continue;
          const size_t i = static_cast<size_t>(py) * static_cast<size_t>(w) + static_cast<size_t>(px);
          if (!object[i]) continue;
          const double g = weights[static_cast<size_t>(dx + radius)] * weights[static_cast<size_t>(dy + radius)];
          const double a = x.at(i), b = y.at(i);
          sw += g;
          mx += g * a;
          my += g * b;
          mxx += g * a * a;
          myy += g * b * b;
          mxy += g * a * b;
        }
      }
      mx /= sw, my /= sw;
      const double vx = std::max(0.0, mxx / sw - mx * mx), vy = std::max(0.0, myy / sw - my * my);
      const double cov = mxy / sw - mx * my;
      total += ((2.0 * mx * my + c1) * (2.0 * cov + c2)) / ((mx * mx + my * my + c1) * (vx + vy + c2));
      ++count;
    }
  }
  return count ? total / static_cast<double>(count) : std::numeric_limits<double>::quiet_NaN();
}

// Mean |e - box(e)| over object pixels, box over the object pixels of a (2r+1)^2 window.
double high_frequency(const std::vector<double>& error, const std::vector<uint8_t>& object, int w, int h, int radius) {
  // Summed-area tables of the error and of the object count make every window O(1).
  const auto at = [w](int x, int y) { return static_cast<size_t>(y) * static_cast<size_t>(w + 1) + static_cast<size_t>(x); };
  std::vector<double> sum(static_cast<size_t>(w + 1) * static_cast<size_t>(h + 1), 0.0);
  std::vector<double> count(sum.size(), 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x);
      const double e = object[i] ? error[i] : 0.0;
      sum[at(x + 1, y + 1)] = e + sum[at(x, y + 1)] + sum[at(x + 1, y)] - sum[at(x, y)];
      count[at(x + 1, y + 1)] = (object[i] ? 1.0 : 0.0) + count[at(x, y + 1)] + count[at(x + 1, y)] - count[at(x, y)];
    }
  double total = 0.0;
  size_t n = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x);
      if (!object[i]) continue;
      const int x0 = std::max(0, x - radius), x1 = std::min(w, x + radius + 1);
      const int y0 = std::max(0, y - radius), y1 = std::min(h, y + radius + 1);
      const double s = sum[at(x1, y1)] - sum[at(x0, y1)] - sum[at(x1, y0)] + sum[at(x0, y0)];
      const double c = count[at(x1, y1)] - count[at(x0, y1)] - count[at(x1, y0)] + count[at(x0, y0)];
      total += std::abs(error[i] - s / c);
      ++n;
    }
  return n ? total / static_cast<double>(n) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

std::vector<uint8_t> edge_mask(const Image& depth, const MetricsSettings& settings) {
  const int w = depth.width, h = depth.height;
  const auto index = [w](int x, int y) { return static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x); };
  std::vector<uint8_t> edge(depth.pixel_count(), 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const double d = depth.at(index(x, y));
      if (!(d > 0.0)) continue;
      const int neighbours[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
      for (const auto& n : neighbours) {
        if (n[0] < 0 || n[0] >= w || n[1] < 0 || n[1] >= h) continue;  // the frame's border is no edge
        const double e = depth.at(index(n[0], n[1]));
        if (!(e > 0.0) || std::abs(d - e) > settings.edge_jump * std::min(d, e)) {
          edge[index(x, y)] = 1;
          break;
        }
      }
    }
  }
  const int k = std::max(0, settings.edge_distance);
  std::vector<uint8_t> near(depth.pixel_count(), 0);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      if (!(depth.at(index(x, y)) > 0.0)) continue;
      for (int py = std::max(0, y - k); py <= std::min(h - 1, y + k) && !near[index(x, y)]; ++py)
        for (int px = std::max(0, x - k); px <= std::min(w - 1, x + k); ++px)
          if (edge[index(px, py)]) {
            near[index(x, y)] = 1;
            break;
          }
    }
  }
  return near;
}

Metrics compare(const Image& estimate, const Image& reference, const Image& depth, const MetricsSettings& settings) {
  if (!estimate.same_size(reference) || !estimate.same_size(depth) || estimate.channels < 1 || reference.channels < 1 ||
      depth.channels < 1)
    throw std::invalid_argument("aoref::compare: expected estimate, reference and depth of one size, found " +
                                size_text(estimate) + ", " + size_text(reference) + " and " + size_text(depth));
  std::vector<uint8_t> object(depth.pixel_count());
  for (size_t i = 0; i < object.size(); ++i) object[i] = depth.at(i) > 0.0f ? 1 : 0;
  const std::vector<uint8_t> near_edge = edge_mask(depth, settings);

  Metrics m;
  double abs_sum = 0.0, square_sum = 0.0, signed_sum = 0.0, edge_sum = 0.0;
  std::vector<double> error(object.size(), 0.0);
  for (size_t i = 0; i < object.size(); ++i) {
    if (!object[i]) continue;
    const double difference = static_cast<double>(estimate.at(i)) - reference.at(i);
    error[i] = difference;
    abs_sum += std::abs(difference);
    square_sum += difference * difference;
    signed_sum += difference;
    ++m.pixels;
    if (near_edge[i]) {
      edge_sum += std::abs(difference);
      ++m.edge_pixels;
    }
  }
  constexpr double nan = std::numeric_limits<double>::quiet_NaN();
  const double n = static_cast<double>(m.pixels);
  m.mae = m.pixels ? abs_sum / n : nan;
  m.rmse = m.pixels ? std::sqrt(square_sum / n) : nan;
  m.bias = m.pixels ? signed_sum / n : nan;
  m.edge_mae = m.edge_pixels ? edge_sum / static_cast<double>(m.edge_pixels) : nan;
  m.ssim = masked_ssim(estimate, reference, object, settings);
  m.noise = high_frequency(error, object, estimate.width, estimate.height, std::max(0, settings.noise_radius));
  return m;
}

std::vector<int64_t> match_previous(const Image& position_now, const Image& position_before,
                                    const glm::dmat4& view_projection_before, const glm::dvec3& eye_before, double tolerance) {
  if (!position_now.same_size(position_before) || position_now.channels < 4 || position_before.channels < 4)
    throw std::invalid_argument("aoref::match_previous: expected two position images (4 channels) of one size, found " +
                                size_text(position_now) + " and " + size_text(position_before));
  const int w = position_now.width, h = position_now.height;
  std::vector<int64_t> match(position_now.pixel_count(), -1);
  for (size_t i = 0; i < match.size(); ++i) {
    if (!(position_now.at(i, 3) > 0.0f)) continue;
    const glm::dvec3 world(position_now.at(i, 0), position_now.at(i, 1), position_now.at(i, 2));
    const glm::dvec4 clip = view_projection_before * glm::dvec4(world, 1.0);
    if (!(clip.w > 0.0)) continue;
    const double u = (clip.x / clip.w * 0.5 + 0.5) * w, v = (0.5 - clip.y / clip.w * 0.5) * h;  // v: rows top-down
    if (!(u >= 0.0 && u < w && v >= 0.0 && v < h)) continue;
    const size_t j = static_cast<size_t>(std::floor(v)) * static_cast<size_t>(w) + static_cast<size_t>(std::floor(u));
    if (!(position_before.at(j, 3) > 0.0f)) continue;
    const glm::dvec3 seen(position_before.at(j, 0), position_before.at(j, 1), position_before.at(j, 2));
    if (glm::length(seen - world) <= tolerance * glm::length(world - eye_before)) match[i] = static_cast<int64_t>(j);
  }
  return match;
}

double mean_change(const Image& now, const Image& before, const std::vector<int64_t>& match) {
  double total = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < match.size(); ++i) {
    if (match[i] < 0) continue;
    total += std::abs(static_cast<double>(now.at(i)) - before.at(static_cast<size_t>(match[i])));
    ++n;
  }
  return n ? total / static_cast<double>(n) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace aoref
