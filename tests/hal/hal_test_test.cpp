// `player hal-test` on the mock backend, end to end.
#include <gtest/gtest.h>
#include <sys/resource.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "hal/hal_test.h"
#include "hal/image.h"

namespace hal {
namespace {

TEST(HalTest, MockBoardPrintsEventsCyclesLedsAndSavesACapture) {
  const std::string capture = std::string(HAL_TEST_OUTPUT_DIR) + "/hal-test-capture.png";
  std::filesystem::remove(capture);
  HalTestOptions o;
  o.capture_path = capture;
  o.duration_s = 1.0;
  std::ostringstream out;
  const int rc = run_hal_test(o, out);
  const std::string text = out.str();
  EXPECT_EQ(rc, 0) << text;
  // Neither --board nor --hal: the built-in mock board, and the first line says so.
  EXPECT_EQ(text.rfind("backend: mock (no --board: the built-in mock board)\n", 0), 0u) << text;
  // The built-in script's bounce on "play" yields one press and one release.
  EXPECT_NE(text.find("button play press"), std::string::npos) << text;
  EXPECT_NE(text.find("button play release"), std::string::npos) << text;
  EXPECT_NE(text.find("button next repeat"), std::string::npos) << text;
  EXPECT_NE(text.find("led status -> on"), std::string::npos) << text;
  // Each LED pattern is shown for a full heartbeat period (1.2 s), so 1 s shows only the first.
  EXPECT_EQ(text.find("led error ->"), std::string::npos) << text;
  EXPECT_NE(text.find("leds: showed 1 of 8 LED patterns; --duration 10 shows them all"), std::string::npos) << text;
  EXPECT_NE(text.find("self-check: pass"), std::string::npos) << text;
  RgbImage img;
  std::string err;
  ASSERT_TRUE(load_image(capture, img, &err)) << err;
  EXPECT_EQ(img.width, 640);
}

TEST(HalTest, BadOptionsAndBoardFilesReturnOne) {
  std::ostringstream out;
  HalTestOptions o;
  o.backend = "gpio";
  EXPECT_EQ(run_hal_test(o, out), 1);
  EXPECT_NE(out.str().find("--hal: expected 'linux' or 'mock', got 'gpio'"), std::string::npos);
  o.backend = "mock";
  o.board_file = "/nonexistent/board.toml";
  EXPECT_EQ(run_hal_test(o, out), 1);
  EXPECT_NE(out.str().find("/nonexistent/board.toml: cannot open the board file (No such file or directory)"), std::string::npos);
}

TEST(HalTest, BoardFileWithoutHalChecksTheRealDevices) {
  // A board file names real hardware: without --hal it is opened on linux, never silently mocked.
  const std::string board = std::string(HAL_TEST_OUTPUT_DIR) + "/no-hal-board.toml";
  std::ofstream(board) << "[board]\nname = \"pi\"\n[[led]]\nname = \"status\"\nline = \"NO_SUCH_LED_LINE\"\n";
  HalTestOptions o;
  o.board_file = board;
  o.duration_s = 0.05;
  std::ostringstream out;
  EXPECT_EQ(run_hal_test(o, out), 2) << out.str();
  EXPECT_EQ(out.str().rfind("backend: linux (--board without --hal; --hal mock simulates the board)\n", 0), 0u) << out.str();
  EXPECT_NE(out.str().find("MISSING: LED 'status': GPIO line NO_SUCH_LED_LINE"), std::string::npos) << out.str();
  // The same board with --hal mock: every device is a mock, so all are present.
  o.backend = "mock";
  std::ostringstream mock_out;
  EXPECT_EQ(run_hal_test(o, mock_out), 0) << mock_out.str();
  EXPECT_EQ(mock_out.str().rfind("backend: mock (--hal mock)\n", 0), 0u) << mock_out.str();
}

// With nothing to blink the loop must sleep in poll() until a button or the end, not wake every
// millisecond. Counted as the thread's voluntary context switches (each sleep in poll() is one),
// not timed: a 1 ms wake-up would make hundreds in half a second, sleeping through makes a few.
TEST(HalTest, BoardWithoutLedsSleepsUntilTheEnd) {
  const std::string board = std::string(HAL_TEST_OUTPUT_DIR) + "/no-led-board.toml";
  std::ofstream(board) << "[board]\nname = \"one button\"\n[[button]]\nname = \"play\"\nline = \"GPIO17\"\n";
  HalTestOptions o;
  o.board_file = board;
  o.backend = "mock";
  o.duration_s = 0.5;
  std::ostringstream out;
  rusage before{}, after{};
  ASSERT_EQ(getrusage(RUSAGE_THREAD, &before), 0);
  EXPECT_EQ(run_hal_test(o, out), 0) << out.str();
  ASSERT_EQ(getrusage(RUSAGE_THREAD, &after), 0);
  EXPECT_LT(after.ru_nvcsw - before.ru_nvcsw, 50) << out.str();
  EXPECT_NE(out.str().find("camera: none on this board"), std::string::npos) << out.str();
}

TEST(HalTest, LinuxBackendWithoutHardwareReportsMissingDevices) {
  const std::string board = std::string(HAL_TEST_OUTPUT_DIR) + "/missing-board.toml";
  std::ofstream(board) << "[board]\nstatus_file = \"" << HAL_TEST_OUTPUT_DIR
                       << "/hal-test-status.json\"\n[[button]]\nname = \"play\"\nchip = \"gpiochip-missing\"\noffset = 1\n"
                          "[camera]\ndevice = \"/dev/video-missing\"\nreopen_interval_ms = 100\n";
  HalTestOptions o;
  o.board_file = board;
  o.backend = "linux";
  o.duration_s = 0.1;
  o.capture_path = std::string(HAL_TEST_OUTPUT_DIR) + "/unused.png";
  std::ostringstream out;
  EXPECT_EQ(run_hal_test(o, out), 2);
  EXPECT_NE(out.str().find("MISSING: button 'play': GPIO chip 'gpiochip-missing'"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("MISSING: camera: /dev/video-missing: cannot open camera"), std::string::npos) << out.str();
  // No display output on linux: the self-check is not run, and the output says why.
  EXPECT_EQ(out.str().find("self-check: pass"), std::string::npos) << out.str();
  std::ifstream in(std::string(HAL_TEST_OUTPUT_DIR) + "/hal-test-status.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_GE(j["errors"].size(), 2u);
}

}  // namespace
}  // namespace hal
