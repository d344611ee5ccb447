// The mock camera's script (player/app/src/camera_script.h): every line is blank, a comment or a
// step, as in button scripts; anything else is refused with the file, the line and the field.
#include "camera_script.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace {

std::string error_of(const std::string& text) {
  std::vector<app::CameraStep> steps;
  std::string error;
  if (app::parse_camera_script_text(text, "camera.script", steps, error)) return "accepted";
  return error;
}

TEST(CameraScript, ReadsStepsCommentsAndBlankLines) {
  std::vector<app::CameraStep> steps;
  std::string error;
  ASSERT_TRUE(app::parse_camera_script_text("# unplugged for a while\n\n300 unplug\n  1000 replug  # back\n1000 unplug\n",
                                            "camera.script", steps, error))
      << error;
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_DOUBLE_EQ(steps[0].at_s, 0.3);
  EXPECT_FALSE(steps[0].plugged);
  EXPECT_DOUBLE_EQ(steps[1].at_s, 1.0);
  EXPECT_TRUE(steps[1].plugged);
  EXPECT_DOUBLE_EQ(steps[2].at_s, 1.0);  // the same time twice: in order
}

// Times that are not whole non-negative milliseconds within a hundred years: nan and infinities
// among them, which once read as a blank line and were skipped.
TEST(CameraScript, RefusesATimeThatIsNotMilliseconds) {
  for (const char* time :
       {"nan", "NaN", "inf", "-inf", "-1", "1.5", "1e3", "0x10", "3153600000001", "99999999999999999999", "abc"})
    EXPECT_EQ(error_of(std::string("100 unplug\n") + time + " replug\n"),
              std::string("camera.script:2: time: expected milliseconds from 0 to 3153600000000 (100 years), got '") + time + "'")
        << time;
}

TEST(CameraScript, RefusesBinaryBytesAndLinesOfOtherShapes) {
  const std::string png_header("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16);
  EXPECT_EQ(error_of(png_header).rfind("camera.script:1: time: expected milliseconds", 0), 0u) << error_of(png_header);
  std::string random_bytes;
  for (int i = 0; i < 512; ++i) random_bytes += static_cast<char>((i * 167 + 13) % 256);
  EXPECT_NE(error_of(random_bytes), "accepted");
  EXPECT_EQ(error_of("100 unplug\n50 replug\n"), "camera.script:2: time: expected times that do not decrease, got 50 after 100");
  EXPECT_EQ(error_of("100 unplugged\n"), "camera.script:1: action: expected 'unplug' or 'replug', got 'unplugged'");
  EXPECT_EQ(error_of("100\n"), "camera.script:1: action: expected 'unplug' or 'replug', got ''");
  EXPECT_EQ(error_of("100 unplug now\n"), "camera.script:1: expected 2 fields, got more: 'now'");
}

}  // namespace
