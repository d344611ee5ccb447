// The display self-check's pass/fail matrix under the mock camera's distortions, with the margin
// between the worst pass and the best fail printed (the number the pass threshold is chosen from).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>

#include "hal/board.h"
#include "hal/image.h"
#include "hal/mock.h"
#include "hal/self_check.h"

namespace hal {
namespace {

constexpr int kW = 640, kH = 360;

CameraModel model(double tilt, double blur, double noise, double exposure, double gamma, double vignetting, std::uint32_t seed) {
  CameraModel m;
  m.screen_corners = {{{60 + tilt, 80}, {580, 70 + tilt}, {570 - tilt, 400}, {70, 410 - tilt}}};
  m.blur_sigma = blur;
  m.noise_sigma = noise;
  m.exposure = exposure;
  m.gamma = gamma;
  m.vignetting = vignetting;
  m.seed = seed;
  return m;
}

RgbImage with_markers(RgbImage img, const FiducialLayout& l) {
  draw_fiducials(img, l);
  return img;
}

// The picture moved on the panel by (dx, dy) and scaled about the centre; what falls off is lost.
RgbImage transform(const RgbImage& src, int dx, int dy, double scale) {
  RgbImage out(src.width, src.height);
  for (int y = 0; y < src.height; ++y)
    for (int x = 0; x < src.width; ++x) {
      const int sx = static_cast<int>(std::lround((x - dx - src.width / 2.0) / scale + src.width / 2.0));
      const int sy = static_cast<int>(std::lround((y - dy - src.height / 2.0) / scale + src.height / 2.0));
      if (sx >= 0 && sy >= 0 && sx < src.width && sy < src.height) std::copy_n(src.at(sx, sy), 3, out.at(x, y));
    }
  return out;
}

struct Case {
  std::string name;
  RgbImage displayed;
  CameraModel camera;
  bool expect_pass;
};

TEST(SelfCheck, PassFailMatrixAndMargin) {
  const FiducialLayout layout = FiducialLayout::for_display(kW, kH, 7);
  const FiducialLayout previous_layout = FiducialLayout::for_display(kW, kH, 6);
  const RgbImage scene = make_test_scene(kW, kH, 1, 2.0);
  const RgbImage presented = with_markers(scene, layout);
  const CameraModel typical = typical_camera_model();

  std::vector<Case> cases;
  // Correct frames under camera distortions.
  cases.push_back({"typical webcam", presented, typical, true});
  cases.push_back({"frontal, sharp", presented, model(0, 0, 0, 1, 1, 0, 1), true});
  cases.push_back({"strong perspective", presented, model(40, 0.8, 2, 1, 1, 0.2, 2), true});
  cases.push_back({"lens blur 1.5 px", presented, model(10, 1.5, 2, 1, 1, 0.1, 3), true});
  cases.push_back({"noise sigma 6", presented, model(10, 0.7, 6, 1, 1, 0.1, 4), true});
  cases.push_back({"under-exposed, gamma 1.4", presented, model(10, 0.7, 2, 0.6, 1.4, 0.2, 5), true});
  cases.push_back({"over-exposed, gamma 0.8", presented, model(10, 0.7, 2, 1.25, 0.8, 0.1, 6), true});
  cases.push_back({"strong vignetting", presented, model(10, 0.7, 2, 1, 1, 0.45, 7), true});

  // Wrong pictures.
  cases.push_back({"black screen", RgbImage(kW, kH), typical, false});
  cases.push_back({"black content, markers shown", with_markers(RgbImage(kW, kH), layout), typical, false});
  cases.push_back(
      {"frozen: previous check frame", with_markers(make_test_scene(kW, kH, 1, 1.5), previous_layout), typical, false});
  cases.push_back(
      {"frozen content (0.5 s old), current markers", with_markers(make_test_scene(kW, kH, 1, 1.5), layout), typical, false});
  cases.push_back({"wrong scene", with_markers(make_test_scene(kW, kH, 2, 2.0), layout), typical, false});
  cases.push_back({"wrong scene 2", with_markers(make_test_scene(kW, kH, 4, 2.0), layout), typical, false});
  cases.push_back({"picture shifted 24 px on the panel", transform(presented, 24, 0, 1.0), typical, false});
  cases.push_back({"picture cropped by overscan 5%", transform(presented, 0, 0, 1.05), typical, false});
  cases.push_back(
      {"content shifted 24 px, markers in place", with_markers(transform(scene, 24, 0, 1.0), layout), typical, false});
  cases.push_back(
      {"content shifted 12 px down, markers in place", with_markers(transform(scene, 0, 12, 1.0), layout), typical, false});
  cases.push_back({"content cropped 10%, markers in place", with_markers(transform(scene, 0, 0, 1.10), layout), typical, false});

  // Other scenes, each checked against itself.
  std::vector<std::pair<RgbImage, RgbImage>> own;  // (presented, displayed)
  for (int s : {0, 2, 3, 5}) {
    const RgbImage other = with_markers(make_test_scene(kW, kH, s, 0.5), layout);
    cases.push_back({"scene " + std::to_string(s) + ", correct", other, model(15, 1.0, 3, 0.8, 1.2, 0.3, 10 + s), true});
  }

  DisplayChecker checker;
  double worst_pass = 2, best_fail = -2;
  std::string worst_pass_name, best_fail_name;
  std::printf("%-48s %-6s %8s %s\n", "case", "result", "SSIM", "reason");
  for (const Case& c : cases) {
    RgbImage capture;
    synthesize_capture(c.displayed, c.camera, 0, capture);
    // The "correct" cases of other scenes present what they display; all others present `presented`.
    const bool own_frame = c.name.find(", correct") != std::string::npos;
    const SelfCheckResult r = checker.check(own_frame ? c.displayed : presented, layout, capture);
    std::printf("%-48s %-6s %8.4f %s\n", c.name.c_str(), r.passed ? "pass" : "FAIL", r.score, r.reason.c_str());
    EXPECT_EQ(r.passed, c.expect_pass) << c.name << ": " << r.reason;
    if (c.expect_pass && r.score < worst_pass) worst_pass = r.score, worst_pass_name = c.name;
    if (!c.expect_pass && r.registered && r.score > best_fail) best_fail = r.score, best_fail_name = c.name;
  }
  std::printf("margin: worst pass %.4f (%s), best registered fail %.4f (%s), threshold %.2f, gap %.4f\n", worst_pass,
              worst_pass_name.c_str(), best_fail, best_fail_name.c_str(), SelfCheckOptions{}.pass_threshold,
              worst_pass - best_fail);
  EXPECT_GT(worst_pass - best_fail, 0.1) << "threshold has too little room on one side";
}

// A screen that is mostly flat (a grey page with one picture on it) and shows the wrong picture must
// fail: the comparison weighs each window by its contrast, so the flat windows, which look alike
// whatever is shown, do not outvote the ones that can tell the pictures apart. Averaged plainly,
// the page's flat windows carried the wrong picture past the threshold. The right picture passes.
TEST(SelfCheck, AWrongPictureOnAMostlyFlatScreenFails) {
  const FiducialLayout layout = FiducialLayout::for_display(kW, kH, 3);
  auto page_with = [&](int scene) {
    RgbImage page(kW, kH);
    std::fill(page.pixels.begin(), page.pixels.end(), std::uint8_t{128});
    // A picture of 128 x 96 in the middle of the page: about 5% of the screen.
    const RgbImage picture = make_test_scene(kW, kH, scene, 2.0);
    for (int y = kH / 2 - 48; y < kH / 2 + 48; ++y)
      for (int x = kW / 2 - 64; x < kW / 2 + 64; ++x) std::copy_n(picture.at(x, y), 3, page.at(x, y));
    return with_markers(page, layout);
  };
  const RgbImage presented = page_with(1);
  DisplayChecker checker;
  RgbImage capture;
  synthesize_capture(presented, typical_camera_model(), 0, capture);
  const SelfCheckResult right = checker.check(presented, layout, capture);
  EXPECT_TRUE(right.passed) << right.reason;
  for (int other : {2, 4}) {
    synthesize_capture(page_with(other), typical_camera_model(), 0, capture);
    const SelfCheckResult wrong = checker.check(presented, layout, capture);
    EXPECT_TRUE(wrong.registered) << wrong.reason;
    EXPECT_FALSE(wrong.passed) << "scene " << other << " shown for scene 1: SSIM " << wrong.score;
  }
}

TEST(SelfCheck, MarkersUseTheCheckSequence) {
  const auto a = FiducialLayout::for_display(1920, 1080, 0), b = FiducialLayout::for_display(1920, 1080, 1);
  EXPECT_EQ(a.first_id, 0);
  EXPECT_EQ(b.first_id, 4);
  EXPECT_EQ(a.marker_size(), 180);
  EXPECT_EQ(a.marker_origin(2), (std::array<int, 2>{1740, 900}));
}

TEST(SelfCheck, MismatchedSizesAreAnErrorNotACrash) {
  DisplayChecker checker;
  const auto layout = FiducialLayout::for_display(kW, kH, 0);
  const SelfCheckResult r = checker.check(RgbImage(100, 100), layout, RgbImage(640, 480));
  EXPECT_FALSE(r.passed);
  EXPECT_NE(r.reason.find("expected the layout's 640x360"), std::string::npos) << r.reason;
}

// A PNG of a signature, an IHDR chunk claiming `width` x `height` RGB, and next to no pixel data,
// which a reader that trusts the header would allocate for before finding out.
std::string png_claiming(std::uint32_t width, std::uint32_t height) {
  const auto crc32 = [](const std::string& bytes) {
    std::uint32_t crc = 0xFFFFFFFFu;
    for (unsigned char byte : bytes) {
      crc ^= byte;
      for (int bit = 0; bit < 8; ++bit) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
    }
    return ~crc;
  };
  const auto big_endian = [](std::uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8), static_cast<char>(v)};
  };
  const auto chunk = [&](const std::string& type, const std::string& data) {
    return big_endian(static_cast<std::uint32_t>(data.size())) + type + data + big_endian(crc32(type + data));
  };
  const std::string header = big_endian(width) + big_endian(height) + std::string("\x08\x02\x00\x00\x00", 5);
  // An empty zlib stream as the only data: a reader learns the size from IHDR before it gets here.
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", header) +
         chunk("IDAT", std::string("\x78\x9c\x03\x00\x00\x00\x00\x01", 8)) + chunk("IEND", "");
}

TEST(MockCamera, AnImageWhoseHeaderClaimsTooManyPixelsIsRefusedBeforeAllocating) {
  const std::string path = std::string(HAL_TEST_OUTPUT_DIR) + "/claims-60000.png";
  std::ofstream(path, std::ios::binary) << png_claiming(60000, 60000);
  RgbImage image;
  std::string err;
  EXPECT_FALSE(load_image(path, image, &err));
  EXPECT_EQ(err, path + ": the image is 60000x60000; at most 16384 pixels per side and 64 million pixels are read");
  // Within each side, beyond the pixel budget.
  std::ofstream(path, std::ios::binary) << png_claiming(16000, 16000);
  EXPECT_FALSE(load_image(path, image, &err));
  EXPECT_EQ(err, path + ": the image is 16000x16000; at most 16384 pixels per side and 64 million pixels are read");
  // As a mock camera's frame: the board's start-up fails with the same reason, not std::bad_alloc.
  ManualClock clock(std::chrono::seconds(10));
  try {
    MockCamera camera({path}, clock);
    ADD_FAILURE() << "the mock camera took " << path;
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "mock camera: " + err);
  }
}

TEST(MockCamera, CyclesImageFilesAtItsFrameRateAndSimulatesUnplug) {
  const std::string dir = HAL_TEST_OUTPUT_DIR;
  std::string err;
  RgbImage a(8, 4), b(8, 4);
  b.at(1, 1)[0] = 200;
  ASSERT_TRUE(save_image(dir + "/mock_a.png", a, &err)) << err;
  ASSERT_TRUE(save_image(dir + "/mock_b.png", b, &err)) << err;
  ManualClock clock(std::chrono::seconds(10));
  MockCamera cam({dir + "/mock_a.png", dir + "/mock_b.png"}, clock);
  RgbImage f;
  ASSERT_TRUE(cam.capture(f, std::chrono::milliseconds(100)));
  EXPECT_EQ(f.at(1, 1)[0], 0);
  // Like a webcam, the next frame comes one frame interval later, not on every call.
  EXPECT_FALSE(cam.read_frame(f));
  clock.advance(MockCamera::kFrameInterval - Nanos(1));
  EXPECT_FALSE(cam.read_frame(f));
  clock.advance(Nanos(1));
  ASSERT_TRUE(cam.read_frame(f));
  EXPECT_EQ(f.at(1, 1)[0], 200);
  // Read late: the missed frames are gone and the next is an interval after this read.
  clock.advance(5 * MockCamera::kFrameInterval);
  EXPECT_TRUE(cam.read_frame(f));
  EXPECT_FALSE(cam.read_frame(f));
  cam.unplug();
  EXPECT_EQ(cam.state(), CameraState::lost);
  EXPECT_NE(cam.last_error().find("No such device"), std::string::npos);
  EXPECT_FALSE(cam.read_frame(f));
  cam.service();
  EXPECT_EQ(cam.state(), CameraState::lost);  // still unplugged
  cam.replug();
  cam.service();
  EXPECT_EQ(cam.state(), CameraState::streaming);
  EXPECT_TRUE(cam.last_error().empty());
  EXPECT_TRUE(cam.read_frame(f));
  EXPECT_THROW(MockCamera({dir + "/does-not-exist.png"}, clock), std::runtime_error);
}

}  // namespace
}  // namespace hal
