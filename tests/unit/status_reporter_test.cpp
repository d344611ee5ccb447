// The figures the status file reports about frames, as a monitoring user reads them: the frame
// times' median and 99th percentile over the recent frames, and the rate (fps) as the frames a
// second the median frame time makes, so a few slow frames move p99 and leave the rate alone.
#include "play/status_reporter.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
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

namespace {

// The exposition text as a scraper reads it: each family with its HELP and TYPE, the state one-hot,
// label values escaped, and what has not happened yet (a self-check, a scene load) left out.
TEST(Metrics, TheTextIsWhatPrometheusReads) {
  app::Metrics m;
  m.version = "0.1.0";
  m.platform = "kms";
  m.renderer = "V3D 4.2 \"rpi\"\\x";
  m.start_unix_s = 1700000000.5;
  m.state = "paused";
  m.item = 2;
  m.scene = "/srv/show/a\nb.glb";
  m.frames = 1234;
  m.frame_seconds_sum = 41.0;
  m.frame_intervals = 1233;
  m.frame_seconds_p50 = 0.0333;
  m.frame_seconds_p99 = 0.05;
  m.errors[static_cast<std::size_t>(app::ErrorKind::content)] = 3;
  m.errors[static_cast<std::size_t>(app::ErrorKind::gpu)] = 1;
  m.resident_bytes = 268435456;
  m.display_connected = true;
  m.gpu_resets = 1;
  const std::string text = app::format_metrics(m);
  for (const char* line : {
           "# TYPE ssao_player_info gauge\n",
           "ssao_player_info{version=\"0.1.0\",platform=\"kms\",renderer=\"V3D 4.2 \\\"rpi\\\"\\\\x\"} 1\n",
           "ssao_player_start_time_seconds 1700000000.5\n",
           "ssao_player_state{state=\"starting\"} 0\n",
           "ssao_player_state{state=\"paused\"} 1\n",
           "ssao_player_state{state=\"no_display\"} 0\n",
           "ssao_player_item 2\n",
           "ssao_player_item_info{scene=\"/srv/show/a\\nb.glb\"} 1\n",
           "# TYPE ssao_player_frames_total counter\nssao_player_frames_total 1234\n",
           "# TYPE ssao_player_frame_seconds summary\n",
           "ssao_player_frame_seconds{quantile=\"0.5\"} 0.0333\n",
           "ssao_player_frame_seconds{quantile=\"0.99\"} 0.05\n",
           "ssao_player_frame_seconds_sum 41\nssao_player_frame_seconds_count 1233\n",
           "ssao_player_errors_total{kind=\"content\"} 3\n",
           "ssao_player_errors_total{kind=\"display\"} 0\n",
           "ssao_player_errors_total{kind=\"gpu\"} 1\n",
           "ssao_player_errors_total{kind=\"control\"} 0\n",
           "ssao_player_resident_memory_bytes 268435456\n",
           "ssao_player_display_connected 1\n",
           "ssao_player_gpu_resets_total 1\n",
       })
    EXPECT_NE(text.find(line), std::string::npos) << line << "\nin\n" << text;
  EXPECT_EQ(text.find("ssao_player_self_check"), std::string::npos) << "no self-check has run";
  EXPECT_EQ(text.find("scene_load"), std::string::npos) << "no scene has loaded";
  // Every sample line belongs to the family the TYPE line before it names.
  std::istringstream lines(text);
  std::string family;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("# TYPE ", 0) == 0) {
      family = line.substr(7, line.find(' ', 7) - 7);
    } else if (line[0] != '#') {
      EXPECT_EQ(line.rfind(family, 0), 0u) << line << " after the TYPE of " << family;
    }
  }

  m.item = -1;
  m.self_check = app::Metrics::Check{false, 0.25, 1700000100.0};
  m.scene_load_seconds = 1.5;
  m.state = "no_display";
  m.display_connected = false;
  const std::string later = app::format_metrics(m);
  for (const char* line : {"ssao_player_item -1\n", "ssao_player_self_check_passed 0\n", "ssao_player_self_check_score 0.25\n",
                           "ssao_player_self_check_timestamp_seconds 1700000100\n", "ssao_player_scene_load_seconds 1.5\n",
                           "ssao_player_state{state=\"no_display\"} 1\n", "ssao_player_display_connected 0\n"})
    EXPECT_NE(later.find(line), std::string::npos) << line << "\nin\n" << later;
  EXPECT_EQ(later.find("item_info"), std::string::npos) << "no item on screen, so no scene to name";
}

// The reporter writes the file at each publish, whole, with the errors counted by kind.
TEST(Metrics, TheReporterWritesTheFileWithErrorsByKind) {
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) / "metrics";
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "player.prom").string();
  app::PlayClock clock(true, app::PlayClock::Steady::now(), 0.0, hal::Nanos{0});
  hal::Status board({"status"}, std::make_unique<hal::RecordingLedSink>(clock.devices(), 1), clock.devices(), "");
  app::KioskState kiosk;
  std::ostringstream err;
  app::StatusReporter reporter(board, kiosk, clock, err);
  app::Metrics base;
  base.version = "9.9";
  base.platform = "egl";
  base.renderer = "llvmpipe";
  reporter.open_metrics(file, base);
  reporter.report(app::ErrorKind::content, "a.glb: not a valid glTF");
  reporter.report(app::ErrorKind::content, "a.glb: not a valid glTF");  // once in the status file, twice here
  reporter.report(app::ErrorKind::device, "camera: gone");
  for (int frame = 0; frame < 3; ++frame) {
    if (frame > 0) clock.advance(0.5);
    app::FrameLogLine line;
    line.frame = frame;
    reporter.frame_presented(line);
  }
  hal::StatusReport report;
  report.frames = 3;
  report.item = "a.glb";
  reporter.publish(report, 0);
  std::ifstream in(file);
  ASSERT_TRUE(in) << file;
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const char* line :
       {"ssao_player_info{version=\"9.9\",platform=\"egl\",renderer=\"llvmpipe\"} 1\n",
        "ssao_player_errors_total{kind=\"content\"} 2\n", "ssao_player_errors_total{kind=\"device\"} 1\n",
        "ssao_player_frames_total 3\n", "ssao_player_frame_seconds_sum 1\n", "ssao_player_frame_seconds_count 2\n",
        "ssao_player_item 0\n", "ssao_player_item_info{scene=\"a.glb\"} 1\n", "ssao_player_state{state=\"starting\"} 1\n"})
    EXPECT_NE(text.find(line), std::string::npos) << line << "\nin\n" << text;
  EXPECT_EQ(reporter.errors().size(), 2u);
  // Each state is one label value, "no display" as no_display; a display switched off for the night
  // is still connected, and the file says it is closed.
  const auto read = [&] {
    std::ifstream again(file);
    return std::string((std::istreambuf_iterator<char>(again)), std::istreambuf_iterator<char>());
  };
  reporter.set_display_connected(false);
  kiosk.display_lost();
  reporter.publish(report, 0);
  std::string lost = read();
  EXPECT_NE(lost.find("ssao_player_state{state=\"no_display\"} 1\n"), std::string::npos) << lost;
  EXPECT_NE(lost.find("ssao_player_display_connected 0\n"), std::string::npos) << lost;
  EXPECT_NE(lost.find("ssao_player_open 1\n"), std::string::npos) << lost;
  reporter.set_display_connected(true);
  reporter.set_open(false);
  kiosk.closed();
  reporter.publish(report, 0);
  const std::string closed = read();
  EXPECT_NE(closed.find("ssao_player_state{state=\"closed\"} 1\n"), std::string::npos) << closed;
  EXPECT_NE(closed.find("ssao_player_state{state=\"no_display\"} 0\n"), std::string::npos) << closed;
  EXPECT_NE(closed.find("ssao_player_display_connected 1\n"), std::string::npos) << closed;
  EXPECT_NE(closed.find("ssao_player_open 0\n"), std::string::npos) << closed;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename(), "player.prom") << "nothing left beside it";
  std::filesystem::remove_all(dir);
}

}  // namespace
