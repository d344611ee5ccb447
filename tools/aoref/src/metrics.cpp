#include "aoref/metrics.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace aoref {
namespace {

std::string size_text(const Image& image) { return std::to_string(image.width) + "x" + std::to_string(image.height); }

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
  for (size_t i = 0; i < object.size(); ++i) {
    if (!object[i]) continue;
    const double difference = static_cast<double>(estimate.at(i)) - reference.at(i);
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
  return m;
}

}  // namespace aoref
