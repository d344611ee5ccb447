// Each device's fd wakes a real poll loop on the real clock when its deadline falls, and goes quiet
// once it is serviced, so the app's one poll loop neither sleeps through an event nor spins.
// Deadlines are tens to hundreds of milliseconds and each wait allows 2 s: these check readiness,
// never how fast it came.
#include <gtest/gtest.h>
#include <poll.h>

#include <array>
#include <vector>

#include "hal/mock.h"
#include "hal/status.h"

namespace hal {
namespace {

using std::chrono::milliseconds;

constexpr int kGenerousMs = 2000;

bool readable(int fd, int timeout_ms) {
  pollfd p{fd, POLLIN, 0};
  return poll(&p, 1, timeout_ms) == 1 && (p.revents & POLLIN) != 0;
}

TEST(PollWake, MockButtonsWakeAtTheDebounceAndLongPressDeadlines) {
  MonotonicClock clock;
  MockButtons b({{"play", {milliseconds(30), milliseconds(150), Nanos{0}, milliseconds(100)}}}, {}, clock);
  std::array<ButtonEvent, 4> ev;
  std::vector<ButtonAction> got;
  // What the app's loop does: sleep in poll(), then read whatever is due. False when poll() timed out.
  auto wake_and_read = [&] {
    if (!readable(b.fd(), kGenerousMs)) return false;
    for (std::size_t n; (n = b.read(ev)) > 0;)
      for (std::size_t i = 0; i < n; ++i) got.push_back(ev[i].action);
    return true;
  };
  EXPECT_EQ(b.read(ev), 0u);
  EXPECT_FALSE(readable(b.fd(), 0)) << "nothing pending, yet the fd is readable: the loop would spin";

  // The injection wakes the loop at once; the press is due only when the debounce deadline falls,
  // the long press at its own deadline: each must wake poll() by itself.
  b.inject(0, true);
  for (int wakes = 0; got.size() < 2 && wakes < 5; ++wakes)
    ASSERT_TRUE(wake_and_read()) << "no wake after " << got.size() << " events";
  EXPECT_EQ(got, (std::vector<ButtonAction>{ButtonAction::press, ButtonAction::long_press}));
  // Held, long press sent, no auto-repeat: nothing is due until the release.
  EXPECT_FALSE(readable(b.fd(), 0));

  b.inject(0, false);
  for (int wakes = 0; got.size() < 3 && wakes < 5; ++wakes)
    ASSERT_TRUE(wake_and_read()) << "release debounce did not wake poll()";
  ASSERT_EQ(got.size(), 3u);
  EXPECT_EQ(got[2], ButtonAction::release);
  EXPECT_FALSE(readable(b.fd(), 0));
}

TEST(PollWake, StatusTimerFdWakesAtEachLedEdgeAndSleepsOnSteadyPatterns) {
  MonotonicClock clock;
  auto sink = std::make_unique<RecordingLedSink>(clock, 1);
  auto changes = sink->changes;
  Status status({"status"}, std::move(sink), clock, "");
  status.set_pattern(0, LedPattern::on);
  EXPECT_FALSE(readable(status.fd(), 0)) << "a steady pattern needs no wake-ups";

  changes->clear();
  status.set_pattern(0, LedPattern::blink_slow);  // on already; off 500 ms from now, on again at 1000 ms
  EXPECT_TRUE(changes->empty());
  ASSERT_TRUE(readable(status.fd(), kGenerousMs)) << "the blink's off edge did not wake poll()";
  status.update();
  ASSERT_EQ(changes->size(), 1u);
  EXPECT_FALSE(changes->back().on);
  EXPECT_FALSE(readable(status.fd(), 0)) << "serviced, yet readable before the next edge";
  ASSERT_TRUE(readable(status.fd(), kGenerousMs)) << "the blink's on edge did not wake poll()";
  status.update();
  ASSERT_EQ(changes->size(), 2u);
  EXPECT_TRUE(changes->back().on);

  status.set_pattern(0, LedPattern::off);
  EXPECT_FALSE(readable(status.fd(), 0));
}

TEST(PollWake, MockCameraIsReadableWhenAFrameIsDueAndNotAfterItWasRead) {
  const std::string file = std::string(HAL_TEST_OUTPUT_DIR) + "/poll_frame.png";
  std::string err;
  ASSERT_TRUE(save_image(file, RgbImage(8, 4), &err)) << err;
  MonotonicClock clock;
  // A 1 s frame interval: after a read the fd must stay quiet, and a stall of a second between
  // the read and the check is beyond what a loaded test machine does.
  MockCamera cam({file}, clock, milliseconds(1000));
  RgbImage f;
  ASSERT_TRUE(readable(cam.fd(), kGenerousMs)) << "the first frame is due at once";
  ASSERT_TRUE(cam.read_frame(f));
  EXPECT_FALSE(readable(cam.fd(), 0)) << "frame read, yet the fd is still readable: the loop would spin";
  EXPECT_FALSE(cam.read_frame(f));
  ASSERT_TRUE(readable(cam.fd(), kGenerousMs)) << "the next frame's time did not wake poll()";
  EXPECT_TRUE(cam.read_frame(f));
  EXPECT_FALSE(readable(cam.fd(), 0));

  // Unplugged: one wake so the loop sees it, then quiet until replugged.
  cam.unplug();
  ASSERT_TRUE(readable(cam.fd(), kGenerousMs));
  EXPECT_FALSE(cam.read_frame(f));
  cam.service();
  EXPECT_FALSE(readable(cam.fd(), 0)) << "an unplugged camera must not keep the loop awake";
  cam.replug();
  ASSERT_TRUE(readable(cam.fd(), kGenerousMs));
  cam.service();
  EXPECT_EQ(cam.state(), CameraState::streaming);
  ASSERT_TRUE(readable(cam.fd(), kGenerousMs));
  EXPECT_TRUE(cam.read_frame(f));
}

TEST(PollWake, SyntheticMockCameraSleepsUntilItIsShownAFrame) {
  MonotonicClock clock;
  MockCamera cam(CameraModel{}, clock, milliseconds(1000));
  RgbImage f;
  EXPECT_FALSE(readable(cam.fd(), 0)) << "nothing to film, yet readable";
  EXPECT_FALSE(cam.read_frame(f));
  cam.show(make_test_scene(64, 36, 0, 0.0));
  ASSERT_TRUE(readable(cam.fd(), kGenerousMs));
  EXPECT_TRUE(cam.read_frame(f));
  EXPECT_EQ(f.width, CameraModel{}.width);
  EXPECT_FALSE(readable(cam.fd(), 0));
}

}  // namespace
}  // namespace hal
