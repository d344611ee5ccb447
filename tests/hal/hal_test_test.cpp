// `player hal-test` on the mock backend, end to end.
#include <gtest/gtest.h>

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
  // The built-in script's bounce on "play" yields one press and one release.
  EXPECT_NE(text.find("button play press"), std::string::npos) << text;
  EXPECT_NE(text.find("button play release"), std::string::npos) << text;
  EXPECT_NE(text.find("button next repeat"), std::string::npos) << text;
  EXPECT_NE(text.find("led status -> on"), std::string::npos) << text;
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
  EXPECT_NE(out.str().find("/nonexistent/board.toml: cannot open board file"), std::string::npos);
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
  std::ifstream in(std::string(HAL_TEST_OUTPUT_DIR) + "/hal-test-status.json");
  const auto j = nlohmann::json::parse(in);
  EXPECT_GE(j["errors"].size(), 2u);
}

}  // namespace
}  // namespace hal
