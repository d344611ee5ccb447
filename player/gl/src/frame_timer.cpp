#include "gl/frame_timer.h"

namespace gl {

void FrameTimer::create(bool timer_queries, bool serialise) {
  use_queries_ = timer_queries && api.QueryCounter != nullptr;
  serialise_ = serialise && !use_queries_;
  if (use_queries_)
    for (Slot& slot : ring_)
      for (Query& query : slot.queries) query = make_query();
}

void FrameTimer::stamp(Slot& slot, int index) {
  const auto i = static_cast<size_t>(index);
  if (use_queries_) {
    api.QueryCounter(slot.queries[i].id(), GL_TIMESTAMP_EXT);
  } else if (serialise_) {
    api.Finish();
    slot.cpu[i] = std::chrono::steady_clock::now();
  }
}

void FrameTimer::begin_frame() {
  current_ = static_cast<int>(frame_++ % kRing);
  Slot& slot = ring_[static_cast<size_t>(current_)];
  // A slot whose results were never read is overwritten: the reader fell kRing frames behind.
  slot.marks = 0;
  slot.pending = false;
  if (timed()) stamp(slot, 0);
}

void FrameTimer::mark(int pass) {
  Slot& slot = ring_[static_cast<size_t>(current_)];
  if (!timed() || slot.marks >= kMaxMarks || pass < 0 || pass >= kMaxMarks) return;
  slot.order[static_cast<size_t>(slot.marks)] = pass;
  ++slot.marks;
  stamp(slot, slot.marks);
}

void FrameTimer::end_frame() {
  ring_[static_cast<size_t>(current_)].pending = timed();
}

bool FrameTimer::read(Slot& slot, bool wait, Times& out) {
  if (!slot.pending) return false;
  std::array<double, kMaxMarks + 1> stamps{};
  for (int i = 0; i <= slot.marks; ++i) {
    const auto index = static_cast<size_t>(i);
    if (use_queries_) {
      if (!wait) {
        GLuint available = GL_FALSE;
        api.GetQueryObjectuiv(slot.queries[static_cast<size_t>(slot.marks)].id(), GL_QUERY_RESULT_AVAILABLE, &available);
        if (available == GL_FALSE) return false;  // the last stamp is the latest; when it is there, all are
        wait = true;
      }
      GLuint64 ns = 0;
      api.GetQueryObjectui64v(slot.queries[index].id(), GL_QUERY_RESULT, &ns);
      stamps[index] = static_cast<double>(ns) * 1e-6;
    } else {
      stamps[index] = std::chrono::duration<double, std::milli>(slot.cpu[index] - slot.cpu[0]).count();
    }
  }
  out.fill(-1.0);
  for (int i = 0; i < slot.marks; ++i) {
    const auto index = static_cast<size_t>(i);
    out[static_cast<size_t>(slot.order[index])] = stamps[index + 1] - stamps[index];
  }
  slot.pending = false;
  return true;
}

bool FrameTimer::poll(Times& out) {
  // Oldest first, so that the newest finished frame is what `out` holds at the end.
  bool any = false;
  for (int back = kRing - 1; back >= 0; --back) {
    const long long frame = frame_ - 1 - back;
    if (frame < 0) continue;
    Times times;
    if (read(ring_[static_cast<size_t>(frame % kRing)], false, times)) {
      out = times;
      any = true;
    }
  }
  return any;
}

bool FrameTimer::wait(Times& out) {
  if (frame_ == 0) return false;
  return read(ring_[static_cast<size_t>((frame_ - 1) % kRing)], true, out);
}

}  // namespace gl
