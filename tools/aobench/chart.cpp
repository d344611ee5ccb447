#include "chart.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace aobench {
namespace {
// Debian's fonts-dejavu-core (installed with the project's packages); without it the chart has no labels.
constexpr const char* kFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
}  // namespace

std::vector<size_t> pareto_front(const std::vector<ChartPoint>& points) {
  std::vector<size_t> front;
  for (size_t i = 0; i < points.size(); ++i) {
    bool beaten = false;
    for (size_t j = 0; j < points.size() && !beaten; ++j) {
      if (i == j) continue;
      const bool no_worse = points[j].time_ms <= points[i].time_ms && points[j].error <= points[i].error;
      const bool better = points[j].time_ms < points[i].time_ms || points[j].error < points[i].error;
      beaten = no_worse && (better || j < i);
    }
    if (!beaten) front.push_back(i);
  }
  std::sort(front.begin(), front.end(), [&](size_t a, size_t b) { return points[a].time_ms < points[b].time_ms; });
  return front;
}

bool write_chart(const std::string& path, const std::vector<ChartPoint>& points, const std::string& title,
                 const std::string& error_label, std::string& error) {
  constexpr int kWidth = kChartLayout.width, kHeight = kChartLayout.height, kLeft = kChartLayout.left,
                kRight = kChartLayout.right, kTop = kChartLayout.top, kBottom = kChartLayout.bottom;
  OIIO::ImageBuf chart(OIIO::ImageSpec(kWidth, kHeight, 3, OIIO::TypeDesc::UINT8));
  OIIO::ImageBufAlgo::fill(chart, {1.0f, 1.0f, 1.0f});
  if (points.empty()) {
    error = path + ": no points to chart";
    return false;
  }
  double t_min = 1e300, t_max = 0.0, e_max = 0.0;
  for (const ChartPoint& p : points) {
    t_min = std::min(t_min, std::max(p.time_ms, 1e-3));
    t_max = std::max(t_max, std::max(p.time_ms, 1e-3));
    e_max = std::max(e_max, p.error);
  }
  const double log_min = std::log10(t_min) - kTimePadDecades, log_max = std::log10(t_max) + kTimePadDecades;
  e_max = e_max > 0.0 ? e_max * kErrorHeadroom : 1.0;
  auto x_of = [&](double t) {
    return kLeft + static_cast<int>((std::log10(std::max(t, 1e-3)) - log_min) / (log_max - log_min) * (kWidth - kLeft - kRight));
  };
  auto y_of = [&](double e) { return kHeight - kBottom - static_cast<int>(e / e_max * (kHeight - kTop - kBottom)); };
  const float axis[3] = {0.2f, 0.2f, 0.2f}, grid[3] = {0.88f, 0.88f, 0.88f};
  // Grid: decades and their 2x, 5x on the time axis; five steps on the error axis.
  for (int decade = static_cast<int>(std::floor(log_min)); decade <= static_cast<int>(std::ceil(log_max)); ++decade)
    for (double m : {1.0, 2.0, 5.0}) {
      const double t = m * std::pow(10.0, decade);
      if (std::log10(t) < log_min || std::log10(t) > log_max) continue;
      const int x = x_of(t);
      OIIO::ImageBufAlgo::render_line(chart, x, kTop, x, kHeight - kBottom, grid);
      char label[32];
      std::snprintf(label, sizeof label, "%g", t);
      OIIO::ImageBufAlgo::render_text(chart, x - 12, kHeight - kBottom + 24, label, 16, kFont, axis);
    }
  for (int step = 0; step <= 5; ++step) {
    const double e = e_max * step / 5.0;
    const int y = y_of(e);
    OIIO::ImageBufAlgo::render_line(chart, kLeft, y, kWidth - kRight, y, grid);
    char label[32];
    std::snprintf(label, sizeof label, "%.3f", e);
    OIIO::ImageBufAlgo::render_text(chart, 20, y + 6, label, 16, kFont, axis);
  }
  OIIO::ImageBufAlgo::render_line(chart, kLeft, kHeight - kBottom, kWidth - kRight, kHeight - kBottom, axis);
  OIIO::ImageBufAlgo::render_line(chart, kLeft, kTop, kLeft, kHeight - kBottom, axis);
  OIIO::ImageBufAlgo::render_text(chart, kWidth / 2 - 160, kHeight - 30, "AO time per frame, ms (log scale)", 20, kFont, axis);
  OIIO::ImageBufAlgo::render_text(chart, kLeft, 40, title + "   y: " + error_label, 20, kFont, axis);

  const auto& dot = kPointColour;
  const auto& front = kFrontColour;
  for (const ChartPoint& p : points)
    OIIO::ImageBufAlgo::render_box(chart, x_of(p.time_ms) - 2, y_of(p.error) - 2, x_of(p.time_ms) + 2, y_of(p.error) + 2, dot,
                                   true);
  const std::vector<size_t> on_front = pareto_front(points);
  for (size_t i = 0; i + 1 < on_front.size(); ++i) {
    const ChartPoint &a = points[on_front[i]], &b = points[on_front[i + 1]];
    OIIO::ImageBufAlgo::render_line(chart, x_of(a.time_ms), y_of(a.error), x_of(b.time_ms), y_of(b.error), front);
  }
  for (size_t i : on_front)
    OIIO::ImageBufAlgo::render_box(chart, x_of(points[i].time_ms) - 4, y_of(points[i].error) - 4, x_of(points[i].time_ms) + 4,
                                   y_of(points[i].error) + 4, front, true);
  const auto& marked = kMarkColour;
  for (const ChartPoint& p : points) {
    if (p.mark.empty()) continue;
    const int x = x_of(p.time_ms), y = y_of(p.error);
    OIIO::ImageBufAlgo::render_box(chart, x - 8, y - 8, x + 8, y + 8, marked, false);
    OIIO::ImageBufAlgo::render_box(chart, x - 7, y - 7, x + 7, y + 7, marked, false);
    OIIO::ImageBufAlgo::render_text(chart, x + 12, y - 10, p.mark, 18, kFont, marked);
  }
  if (!chart.write(path)) {
    error = path + ": cannot write the chart (" + chart.geterror() + ")";
    return false;
  }
  return true;
}

}  // namespace aobench
