// LED pattern timing and the status file.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <thread>

#include "hal/mock.h"
#include "hal/status.h"

namespace hal {
namespace {

using std::chrono::milliseconds;

TEST(LedPatterns, BlinkAndHeartbeatToggleAtTheirPhases) {
  EXPECT_TRUE(pattern_level(LedPattern::blink_slow, milliseconds(0)));
  EXPECT_TRUE(pattern_level(LedPattern::blink_slow, milliseconds(499)));
  EXPECT_FALSE(pattern_level(LedPattern::blink_slow, milliseconds(500)));
  EXPECT_TRUE(pattern_level(LedPattern::blink_slow, milliseconds(1000)));
  EXPECT_EQ(pattern_next_change(LedPattern::blink_slow, milliseconds(700)), milliseconds(1000));
  EXPECT_EQ(pattern_next_change(LedPattern::blink_fast, milliseconds(0)), milliseconds(100));
  EXPECT_EQ(pattern_next_change(LedPattern::on, milliseconds(5)), Nanos::max());
  EXPECT_FALSE(pattern_level(LedPattern::off, milliseconds(5)));
  // Heartbeat: on 0-100, off 100-250, on 250-350, off until 1200.
  const std::pair<int, bool> beat[] = {{0, true},   {99, true},   {100, false},  {249, false}, {250, true},
                                       {349, true}, {350, false}, {1199, false}, {1200, true}};
  for (auto [ms, on] : beat) EXPECT_EQ(pattern_level(LedPattern::heartbeat, milliseconds(ms)), on) << ms;
  // Standby (closed): a 100 ms flash every 3 s.
  const std::pair<int, bool> standby[] = {{0, true}, {99, true}, {100, false}, {2999, false}, {3000, true}, {3100, false}};
  for (auto [ms, on] : standby) EXPECT_EQ(pattern_level(LedPattern::standby, milliseconds(ms)), on) << ms;
  EXPECT_EQ(pattern_next_change(LedPattern::standby, milliseconds(100)), milliseconds(3000));
}

TEST(LedPatterns, PeriodIsOneFullCycle) {
  EXPECT_EQ(pattern_period(LedPattern::blink_slow), milliseconds(1000));
  EXPECT_EQ(pattern_period(LedPattern::blink_fast), milliseconds(200));
  EXPECT_EQ(pattern_period(LedPattern::heartbeat), milliseconds(1200));
  EXPECT_EQ(pattern_period(LedPattern::standby), milliseconds(3000));
  EXPECT_EQ(pattern_period(LedPattern::on), Nanos::max());
  // A period later every pattern is back where it started.
  for (auto p : {LedPattern::blink_slow, LedPattern::blink_fast, LedPattern::heartbeat, LedPattern::standby})
    for (int ms : {0, 90, 150, 300, 600})
      EXPECT_EQ(pattern_level(p, milliseconds(ms)), pattern_level(p, milliseconds(ms) + pattern_period(p))) << ms;
}

TEST(LedPatterns, NamesRoundTrip) {
  for (auto p : {LedPattern::off, LedPattern::on, LedPattern::blink_slow, LedPattern::blink_fast, LedPattern::heartbeat,
                 LedPattern::standby}) {
    LedPattern q = LedPattern::off;
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
  status.set_pattern(0, LedPattern::blink_fast);
  status.set_pattern(1, LedPattern::on);
  for (int i = 0; i < 450; ++i) {
    clock.advance(milliseconds(1));
    status.update();
  }
  std::vector<std::pair<long long, bool>> led0;
  for (const auto& c : *changes)
    if (c.led == 0) led0.push_back({std::chrono::duration_cast<milliseconds>(c.time).count() - 5000, c.on});
  EXPECT_EQ(led0, (std::vector<std::pair<long long, bool>>{{0, true}, {100, false}, {200, true}, {300, false}, {400, true}}));
  ASSERT_EQ(std::count_if(changes->begin(), changes->end(), [](auto& c) { return c.led == 1; }), 1);
  status.set_pattern(0, LedPattern::off);
  EXPECT_FALSE(changes->back().on);
}

TEST(Status, ReportIsWrittenAtomicallyAsJson) {
  const std::string dir = std::string(HAL_TEST_OUTPUT_DIR) + "/status_test";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string file = dir + "/status.json";
  ManualClock clock(milliseconds(1234));
  Status status({"status"}, std::make_unique<RecordingLedSink>(clock, 1), clock, file);
  status.set_pattern(0, LedPattern::heartbeat);
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

// Monitoring tools read the status file while the player rewrites it. Every read, however it falls
// against the writes, must be one whole report: the old one or the new one, never empty or cut off.
// The file lives on /run (a tmpfs) on the boards, so the test uses /dev/shm where it exists: there
// fsync costs nothing and a write takes long enough against a read that a file rewritten in place
// is caught torn on every run.
TEST(Status, ConcurrentReaderNeverSeesAPartialFile) {
  const std::string dir =
      (std::filesystem::is_directory("/dev/shm") ? std::string("/dev/shm") : std::string(HAL_TEST_OUTPUT_DIR)) +
      "/hal_status_atomic_" + std::to_string(::getpid());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string file = dir + "/status.json";
  ManualClock clock;
  Status status({"status"}, std::make_unique<RecordingLedSink>(clock, 1), clock, file);
  // Two reports of very different lengths (about 30 KB and under 1 KB), told apart by their state,
  // each with the error count it must have.
  StatusReport big, small;
  big.state = "big";
  for (int i = 0; i < 300; ++i)
    big.errors.push_back("camera: /dev/video0: cannot open camera: No such file or directory (try " + std::to_string(i) + ")");
  small.state = "small";
  small.errors = {"one"};
  std::string err;
  ASSERT_TRUE(status.write_report(small, &err)) << err;

  constexpr int kWrites = 200;
  std::atomic<bool> done{false};
  std::atomic<int> writes_done{0};
  std::string write_error;
  std::thread writer([&] {
    for (int i = 0; i < kWrites && write_error.empty(); ++i) {
      std::string e;
      if (!status.write_report(i % 2 == 0 ? big : small, &e)) write_error = e;
      writes_done.store(i + 1);
    }
    done.store(true);
  });
  int reads = 0, reads_while_writing = 0, torn = 0;
  std::string first_torn;
  std::string text;
  std::set<std::string> whole;
  // Reads until the writer is done, and at least a few hundred times, so every run reads while writing.
  while (!done.load() || reads < 200) {
    const bool writing = !done.load() && writes_done.load() > 0;
    std::ifstream in(file, std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    ++reads;
    reads_while_writing += writing ? 1 : 0;
    // A text already parsed whole needs no second parse: the reads stay quick and close together,
    // so they land inside the writes (a torn read is never added to `whole`).
    if (whole.count(text) != 0) continue;
    const auto j = nlohmann::json::parse(text, nullptr, false);
    if (!j.is_discarded() && j.is_object() && j.contains("state") && j.contains("errors") &&
        ((j["state"] == "big" && j["errors"].size() == 300u) || (j["state"] == "small" && j["errors"].size() == 1u))) {
      whole.insert(text);
      continue;
    }
    if (torn++ == 0)
      first_torn = std::to_string(text.size()) + " bytes: '" + text.substr(0, 40) + "' ... '" +
                   text.substr(text.size() > 40 ? text.size() - 40 : 0) + "'";
  }
  writer.join();
  EXPECT_EQ(write_error, "");
  EXPECT_EQ(writes_done.load(), kWrites);
  EXPECT_GT(reads_while_writing, 0) << "the reader never overlapped the writer; the test proved nothing";
  EXPECT_EQ(torn, 0) << torn << " of " << reads << " reads were not a whole report; the first: " << first_torn;
  // No temporaries left behind, however many writes.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1);
  std::filesystem::remove_all(dir);
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
