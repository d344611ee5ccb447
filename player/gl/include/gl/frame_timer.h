#pragma once
// Per-pass GPU times that never stall the frame: each frame writes timestamp queries into one slot
// of a small ring, and its results are read a frame or two later, when the GPU has them. Where the
// context has no timer queries, a frame has no pass times (never a glFinish in the frame loop);
// measure() serialises with glFinish for the commands that time on purpose (render, benchmarks).
#include "gl/objects.h"

#include <array>
#include <chrono>

namespace gl {

class FrameTimer {
 public:
  static constexpr int kMaxMarks = 12;
  static constexpr int kRing = 3;               // frames in flight whose times are still to be read
  using Times = std::array<double, kMaxMarks>;  // milliseconds per pass; negative: not marked

  // Creates the queries; call once with a current context. `serialise` (only where timing is the
  // point): without timer queries, time each pass by the CPU clock around a glFinish.
  void create(bool timer_queries, bool serialise);
  bool gpu_timed() const { return use_queries_; }
  bool timed() const { return use_queries_ || serialise_; }

  void begin_frame();
  void mark(int pass);  // the end of `pass`; passes are numbered from 0 and may be skipped
  void end_frame();

  // The newest finished frame's times, without waiting: true when a frame's results arrived since
  // the last call.
  bool poll(Times& out);
  // Waits for the last frame's times (outside the frame loop).
  bool wait(Times& out);

 private:
  struct Slot {
    std::array<Query, kMaxMarks + 1> queries{};
    std::array<std::chrono::steady_clock::time_point, kMaxMarks + 1> cpu{};
    std::array<int, kMaxMarks> order{};
    int marks = 0;
    bool pending = false;
  };
  bool read(Slot& slot, bool wait, Times& out);
  void stamp(Slot& slot, int index);

  bool use_queries_ = false, serialise_ = false;
  std::array<Slot, kRing> ring_{};
  int current_ = 0;
  long long frame_ = 0;
};

}  // namespace gl
