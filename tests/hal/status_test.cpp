// LED pattern timing and the status file.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "hal/mock.h"
#include "hal/status.h"

namespace hal {
namespace {

using std::chrono::milliseconds;

TEST(LedPatterns, BlinkAndHeartbeatToggleAtTheirPhases) {
  EXPECT_TRUE(pattern_level(LedPattern::BlinkSlow, milliseconds(0)));
  EXPECT_TRUE(pattern_level(LedPattern::BlinkSlow, milliseconds(499)));
  EXPECT_FALSE(pattern_level(LedPattern::BlinkSlow, milliseconds(500)));
  EXPECT_TRUE(pattern_level(LedPattern::BlinkSlow, milliseconds(1000)));
  EXPECT_EQ(pattern_next_change(LedPattern::BlinkSlow, milliseconds(700)), milliseconds(1000));
  EXPECT_EQ(pattern_next_change(LedPattern::BlinkFast, milliseconds(0)), milliseconds(100));
  EXPECT_EQ(pattern_next_change(LedPattern::On, milliseconds(5)), Nanos::max());
  EXPECT_FALSE(pattern_level(LedPattern::Off, milliseconds(5)));
  // Heartbeat: on 0-100, off 100-250, on 250-350, off until 1200.
  const std::pair<int, bool> beat[] = {{0, true}, {99, true}, {100, false}, {249, false}, {250, true},
                                       {349, true}, {350, false}, {1199, false}, {1200, true}};
  for (auto [ms, on] : beat) EXPECT_EQ(pattern_level(LedPattern::Heartbeat, milliseconds(ms)), on) << ms;
}

TEST(LedPatterns, PeriodIsOneFullCycle) {
  EXPECT_EQ(pattern_period(LedPattern::BlinkSlow), milliseconds(1000));
  EXPECT_EQ(pattern_period(LedPattern::BlinkFast), milliseconds(200));
  EXPECT_EQ(pattern_period(LedPattern::Heartbeat), milliseconds(1200));
  EXPECT_EQ(pattern_period(LedPattern::On), Nanos::max());
  // A period later every pattern is back where it started.
  for (auto p : {LedPattern::BlinkSlow, LedPattern::BlinkFast, LedPattern::Heartbeat})
    for (int ms : {0, 90, 150, 300, 600})
      EXPECT_EQ(pattern_level(p, milliseconds(ms)), pattern_level(p, milliseconds(ms) + pattern_period(p))) << ms;
}

TEST(LedPatterns, NamesRoundTrip) {
  for (auto p : {LedPattern::Off, LedPattern::On, LedPattern::BlinkSlow, LedPattern::BlinkFast, LedPattern::Heartbeat}) {
    LedPattern q = LedPattern::Off;
    ASSERT_TRUE(parse_led_pattern(to_string(p), q));
    EXPECT_EQ(p, q);
  }
  LedPattern q;
  EXPECT_FALSE(parse_led_pattern("disco", q));
}

// Runs a Status the way the poll loop would, waking at 1 ms steps, and returns the LED's changes.
TEST(Status, DrivesTheSinkAtPatternEdges) {
  ManualClock clock(milliseconds(5000));
  auto sink = std::make_unique<RecordingLedSink>(clock, 2);
  auto changes = sink->changes;
  Status status({"status", "error"}, std::move(sink), clock, "");
  ASSERT_EQ(status.find_led("error"), 1u);
  EXPECT_FALSE(status.find_led("nope").has_value());
  changes->clear();
  status.set_pattern(0, LedPattern::BlinkFast);
  status.set_pattern(1, LedPattern::On);
  for (int i = 0; i < 450; ++i) {
    clock.advance(milliseconds(1));
    status.update();
  }
  std::vector<std::pair<long long, bool>> led0;
  for (const auto& c : *changes)
    if (c.led == 0) led0.push_back({std::chrono::duration_cast<milliseconds>(c.time).count() - 5000, c.on});
  EXPECT_EQ(led0, (std::vector<std::pair<long long, bool>>{{0, true}, {100, false}, {200, true}, {300, false}, {400, true}}));
  ASSERT_EQ(std::count_if(changes->begin(), changes->end(), [](auto& c) { return c.led == 1; }), 1);
  status.set_pattern(0, LedPattern::Off);
  EXPECT_FALSE(changes->back().on);
}

TEST(Status, ReportIsWrittenAtomicallyAsJson) {
  const std::string dir = std::string(HAL_TEST_OUTPUT_DIR) + "/status_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string file = dir + "/status.json";
  ManualClock clock(milliseconds(1234));
  Status status({"status"}, std::make_unique<RecordingLedSink>(clock, 1), clock, file);
  status.set_pattern(0, LedPattern::Heartbeat);
  StatusReport r;
  r.state = "playing";
  r.item = "scenes/sponza.gltf";
  r.errors = {"camera: /dev/video0: cannot open camera: No such file or directory"};
  r.self_check = CheckSummary{true, 0.91, "ok", milliseconds(1200)};
  r.frames = 1800;
  r.fps = 29.5;
  r.frame_ms_p50 = 33.3;
  r.frame_ms_p99 = 41.0;
  std::string err;
  ASSERT_TRUE(status.write_report(r, &err)) << err;
  r.state = "paused";
  ASSERT_TRUE(status.write_report(r, &err)) << err;

  std::ifstream in(file);
  const auto j = nlohmann::json::parse(in);
  EXPECT_EQ(j["state"], "paused");
  EXPECT_EQ(j["item"], "scenes/sponza.gltf");
  EXPECT_EQ(j["errors"].size(), 1u);
  EXPECT_EQ(j["frames"], 1800);
  EXPECT_DOUBLE_EQ(j["fps"].get<double>(), 29.5);
  EXPECT_DOUBLE_EQ(j["frame_ms_p50"].get<double>(), 33.3);
  EXPECT_DOUBLE_EQ(j["frame_ms_p99"].get<double>(), 41.0);
  EXPECT_EQ(j["self_check"]["passed"], true);
  EXPECT_EQ(j["self_check"]["monotonic_ms"], 1200);
  EXPECT_EQ(j["leds"]["status"], "heartbeat");
  // No temporaries left behind.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);
}

TEST(Status, UnwritableStatusFileIsAnErrorNamingIt) {
  ManualClock clock;
  Status status({}, std::make_unique<RecordingLedSink>(clock, 0), clock, "/nonexistent-dir/status.json");
  std::string err;
  EXPECT_FALSE(status.write_report({}, &err));
  EXPECT_NE(err.find("/nonexistent-dir/status.json"), std::string::npos) << err;
  EXPECT_NE(err.find("No such file or directory"), std::string::npos) << err;
}

}  // namespace
}  // namespace hal
