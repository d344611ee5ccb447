#pragma once
// A PNG chart of time against error: every configuration, the Pareto front, and marked points.
#include <string>
#include <vector>

namespace aobench {

struct ChartPoint {
  double time_ms = 0.0, error = 0.0;
  bool on_front = false;
  std::string mark;  // empty, or a label drawn beside a highlighted point ("paper", "default")
};

// Indices of the points no other point beats in both time and error (ties in both count as beaten
// only by an earlier point), sorted by time.
std::vector<size_t> pareto_front(const std::vector<ChartPoint>& points);

// Where write_chart() draws: a width x height RGB image, the plot area inset by the margins. The
// time axis (x) is logarithmic over the points' range padded by kTimePadDecades each side; the error
// axis (y) is linear from 0 at the plot's bottom to kErrorHeadroom x the largest error at its top.
struct ChartLayout {
  int width, height, left, right, top, bottom;
};
inline constexpr ChartLayout kChartLayout{1200, 800, 110, 40, 60, 90};
inline constexpr double kTimePadDecades = 0.05, kErrorHeadroom = 1.08;
// The colours (linear 0..1, written as 8-bit) of every point, the front (its points and the line
// joining them) and marked points (a square outline and the label).
inline constexpr float kPointColour[3] = {0.55f, 0.55f, 0.6f}, kFrontColour[3] = {0.1f, 0.35f, 0.85f},
                       kMarkColour[3] = {0.85f, 0.15f, 0.1f};

// Writes the chart; the time axis is logarithmic. Returns false and says why.
bool write_chart(const std::string& path, const std::vector<ChartPoint>& points, const std::string& title,
                 const std::string& error_label, std::string& error);

}  // namespace aobench
