// The figures the status file reports about frames, as a monitoring user reads them: the frame
// times' median and 99th percentile over the recent frames, and the rate (fps) as the frames a
// second the median frame time makes, so a few slow frames move p99 and leave the rate alone.
#include "play/status_reporter.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "hal/mock.h"

namespace {

TEST(StatusReporter, TheRateIsTheMedianFrameTimesAndSlowFramesShowInP99Only) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "status-reporter";
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "status.json").string();
  app::PlayClock clock(true, app::PlayClock::Steady::now(), 0.0, hal::Nanos{0});
  hal::Status board({"status"}, std::make_unique<hal::RecordingLedSink>(clock.devices(), 1), clock.devices(), file);
  app::KioskState kiosk;
  std::ostringstream err;
  app::StatusReporter reporter(board, kiosk, clock, err);
  // 40 frames 25 ms apart, with a stall of 100 ms after every fifth: 32 intervals of 25 ms and 7 of
  // 100 ms. Their mean (38.5 ms, 26 fps) is not what a kiosk's steady rate is; the median is.
  for (int frame = 0; frame < 40; ++frame) {
    if (frame > 0) clock.advance(frame % 5 == 0 ? 0.100 : 0.025);
    app::FrameLogLine line;
    line.frame = frame;
    line.now = clock.now();
    reporter.frame_presented(line);
  }
  hal::StatusReport report;
  report.frames = 40;
  reporter.publish(report);
  std::ifstream in(file);
  ASSERT_TRUE(in) << file;
  const nlohmann::json status = nlohmann::json::parse(in);
  EXPECT_NEAR(status["frame_ms_p50"].get<double>(), 25.0, 1e-6);
  EXPECT_NEAR(status["frame_ms_p99"].get<double>(), 100.0, 1e-6);
  EXPECT_NEAR(status["fps"].get<double>(), 40.0, 1e-6);
  EXPECT_EQ(status["frames"].get<std::uint64_t>(), 40u);
  std::filesystem::remove_all(dir);
}

}  // namespace
