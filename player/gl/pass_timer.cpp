#include "gl/pass_timer.h"

namespace gl {

void PassTimer::create(bool use_timer_queries) {
  use_queries_ = use_timer_queries && api.QueryCounter != nullptr;
  if (use_queries_)
    for (Query& query : queries_) query = make_query();
}

void PassTimer::begin() {
  marks_ = 0;
  if (use_queries_) {
    api.QueryCounter(queries_[0].id(), GL_TIMESTAMP_EXT);
  } else {
    api.Finish();
    cpu_marks_[0] = std::chrono::steady_clock::now();
  }
}

void PassTimer::mark(int pass) {
  if (marks_ >= kMaxMarks || pass < 0 || pass >= kMaxMarks) return;
  order_[static_cast<size_t>(marks_)] = pass;
  ++marks_;
  if (use_queries_) {
    api.QueryCounter(queries_[static_cast<size_t>(marks_)].id(), GL_TIMESTAMP_EXT);
  } else {
    api.Finish();
    cpu_marks_[static_cast<size_t>(marks_)] = std::chrono::steady_clock::now();
  }
}

std::array<double, PassTimer::kMaxMarks> PassTimer::collect() {
  std::array<double, kMaxMarks> ms;
  ms.fill(-1.0);
  std::array<double, kMaxMarks + 1> stamps{};
  for (int i = 0; i <= marks_; ++i) {
    const auto index = static_cast<size_t>(i);
    if (use_queries_) {
      GLuint64 ns = 0;
      api.GetQueryObjectui64v(queries_[index].id(), GL_QUERY_RESULT, &ns);  // waits for the GPU
      stamps[index] = static_cast<double>(ns) * 1e-6;
    } else {
      stamps[index] = std::chrono::duration<double, std::milli>(cpu_marks_[index] - cpu_marks_[0]).count();
    }
  }
  for (int i = 0; i < marks_; ++i) {
    const auto index = static_cast<size_t>(i);
    ms[static_cast<size_t>(order_[index])] = stamps[index + 1] - stamps[index];
  }
  return ms;
}

}  // namespace gl
