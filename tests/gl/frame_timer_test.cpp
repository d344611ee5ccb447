// Pass times that never stall the frame: each marked pass of a frame gets a time and every other
// pass none, whether the context times on the GPU (timer queries) or the commands that time on
// purpose serialise on the CPU clock; poll() hands over the newest finished frame once, and a frame
// that is not timed has nothing to hand over.
#include "harness.h"

#include "gl/frame_timer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <thread>

namespace {

using Times = gl::FrameTimer::Times;

class FrameTimer : public test::SessionTest {
 protected:
  // Some work for the GPU, so that a pass is more than two stamps back to back.
  static void work() {
    const GLfloat colour[4] = {0.2f, 0.4f, 0.6f, 1.0f};
    gl::api.ClearBufferfv(GL_COLOR, 0, colour);
  }
  // Marked passes have a finite time of at least 0, the others none (negative).
  static void expect_marked_only(const Times& times, std::initializer_list<int> marked) {
    for (int pass = 0; pass < gl::FrameTimer::kMaxMarks; ++pass) {
      const bool expected = std::find(marked.begin(), marked.end(), pass) != marked.end();
      if (expected) {
        EXPECT_TRUE(std::isfinite(times[static_cast<size_t>(pass)]) && times[static_cast<size_t>(pass)] >= 0.0)
            << "pass " << pass << ": " << times[static_cast<size_t>(pass)];
      } else {
        EXPECT_LT(times[static_cast<size_t>(pass)], 0.0) << "pass " << pass << " was not marked";
      }
    }
  }
};

// Serialised on the CPU clock: a pass that slept holds at least that sleep, in the slot of the pass
// it was marked as, whatever order the passes were marked in.
TEST_P(FrameTimer, SerialisedPassesGetTheirOwnTimesInTheirOwnSlots) {
  gl::FrameTimer timer;
  timer.create(false, true);
  ASSERT_TRUE(timer.timed());
  EXPECT_FALSE(timer.gpu_timed());
  Times times{};
  EXPECT_FALSE(timer.wait(times)) << "no frame yet";
  for (const int slow : {5, 2}) {
    timer.begin_frame();
    work();
    timer.mark(5);
    work();
    timer.mark(2);
    if (slow == 2) std::this_thread::sleep_for(std::chrono::milliseconds(30));
    work();
    timer.mark(9);
    timer.end_frame();
    ASSERT_TRUE(timer.wait(times));
    expect_marked_only(times, {5, 2, 9});
    if (slow == 2) {
      EXPECT_GE(times[9], 30.0) << "the sleep came after pass 2's mark: it belongs to pass 9";
    }
  }
  EXPECT_FALSE(timer.wait(times)) << "a frame's times are handed over once";
}

// The passes beyond kMaxMarks in one frame, and pass numbers outside 0..kMaxMarks-1, are not timed;
// every pass up to the limit is.
TEST_P(FrameTimer, AFrameTimesAtMostKMaxMarksPasses) {
  gl::FrameTimer timer;
  timer.create(false, true);
  timer.begin_frame();
  timer.mark(-1);
  timer.mark(gl::FrameTimer::kMaxMarks);
  for (int pass = gl::FrameTimer::kMaxMarks - 1; pass >= 0; --pass) {
    work();
    timer.mark(pass);
  }
  timer.mark(0);  // one more than the limit: ignored, pass 0 keeps its first time
  timer.end_frame();
  Times times{};
  ASSERT_TRUE(timer.wait(times));
  for (int pass = 0; pass < gl::FrameTimer::kMaxMarks; ++pass)
    EXPECT_GE(times[static_cast<size_t>(pass)], 0.0) << "pass " << pass;
}

// poll() never waits: it gives the newest frame whose results are in, once, and the older frames it
// passes over are gone. A frame is kept until kRing newer ones have begun.
TEST_P(FrameTimer, PollGivesTheNewestFinishedFrameOnce) {
  gl::FrameTimer timer;
  timer.create(session_->caps().timer_query, true);
  Times times{};
  EXPECT_FALSE(timer.poll(times)) << "no frame yet";
  for (int frame = 0; frame < gl::FrameTimer::kRing; ++frame) {
    timer.begin_frame();
    work();
    timer.mark(frame);  // frame k marks pass k only: which frame `times` holds shows in its marks
    timer.end_frame();
  }
  gl::api.Finish();
  bool any = false;
  for (int attempt = 0; attempt < 1000 && !any; ++attempt) {
    any = timer.poll(times);
    if (!any) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(any);
  expect_marked_only(times, {gl::FrameTimer::kRing - 1});
  EXPECT_FALSE(timer.poll(times)) << "handed over already, the older frames with it";
  EXPECT_FALSE(timer.wait(times));

  // kRing + 1 frames unread: the first of them was overwritten by the last; poll gives the last.
  for (int frame = 0; frame <= gl::FrameTimer::kRing; ++frame) {
    timer.begin_frame();
    work();
    timer.mark(frame);
    timer.end_frame();
  }
  gl::api.Finish();
  any = false;
  for (int attempt = 0; attempt < 1000 && !any; ++attempt) {
    any = timer.poll(times);
    if (!any) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(any);
  expect_marked_only(times, {gl::FrameTimer::kRing});
  EXPECT_FALSE(timer.wait(times));
}

// On the GPU's clock where the context has timer queries (EXT_disjoint_timer_query, or desktop GL).
TEST_P(FrameTimer, GpuTimedPassesGetTheirOwnTimes) {
  gl::FrameTimer timer;
  timer.create(session_->caps().timer_query, false);
  EXPECT_EQ(timer.gpu_timed(), session_->caps().timer_query);
  EXPECT_EQ(timer.timed(), session_->caps().timer_query) << "without queries and not serialised: untimed";
  timer.begin_frame();
  work();
  timer.mark(1);
  work();
  timer.mark(7);
  timer.end_frame();
  Times times{};
  if (!session_->caps().timer_query) {
    EXPECT_FALSE(timer.wait(times)) << "an untimed frame has no times";
    EXPECT_FALSE(timer.poll(times));
    return;
  }
  ASSERT_TRUE(timer.wait(times));
  expect_marked_only(times, {1, 7});
}

// Neither timer queries nor serialising (the frame loop on a driver without queries): nothing is
// timed, and nothing waits.
TEST_P(FrameTimer, AnUntimedFrameHasNoTimes) {
  gl::FrameTimer timer;
  timer.create(false, false);
  EXPECT_FALSE(timer.timed());
  EXPECT_FALSE(timer.gpu_timed());
  timer.begin_frame();
  work();
  timer.mark(0);
  timer.end_frame();
  Times times{};
  EXPECT_FALSE(timer.poll(times));
  EXPECT_FALSE(timer.wait(times));
}

INSTANTIATE_TEST_SUITE_P(Platforms, FrameTimer, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace
