#pragma once
// Per-pass GPU times from timestamp queries; where the context has none, CPU time around a
// glFinish at each mark, which serialises the GPU and so is reported as such.
#include "gl/objects.h"

#include <array>
#include <chrono>

namespace gl {

class PassTimer {
 public:
  static constexpr int kMaxMarks = 12;

  PassTimer() = default;
  // Creates the queries; call once with a current context.
  void create(bool use_timer_queries);

  void begin();
  void mark(int pass);  // the end of `pass`; passes are numbered from 0 and may be skipped
  // Waits for the results of the frame; milliseconds per pass, negative for passes not marked.
  std::array<double, kMaxMarks> collect();
  bool gpu_timed() const { return use_queries_; }

 private:
  bool use_queries_ = false;
  std::array<Query, kMaxMarks + 1> queries_{};
  std::array<std::chrono::steady_clock::time_point, kMaxMarks + 1> cpu_marks_{};
  std::array<int, kMaxMarks> order_{};  // pass number of each mark, in order
  int marks_ = 0;
};

}  // namespace gl
