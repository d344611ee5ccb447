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

// Writes the chart; the time axis is logarithmic. Returns false and says why.
bool write_chart(const std::string& path, const std::vector<ChartPoint>& points, const std::string& title,
                 const std::string& error_label, std::string& error);

}  // namespace aobench
