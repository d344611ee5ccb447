// Golden images of the built-in demo. A failure writes the actual picture and a diff image to the
// build's test-output folder; tools/accept-goldens copies the actual pictures over the goldens.
#include "harness.h"

#include <OpenImageIO/imageio.h>

#include <filesystem>

namespace {

// Both platforms run Mesa's llvmpipe, which is deterministic for a given Mesa and LLVM build; the
// tolerance absorbs what differs between machines: the rasteriser's SIMD width and fused
// multiply-adds move an edge pixel or a sample near a depth boundary. 5/255 is below what the eye
// separates in a smooth gradient; 0.5% of pixels (61 of 12288) covers silhouette pixels that flip.
constexpr int kMaxChannelDifference = 5;
constexpr double kMaxFailingShare = 0.005;

struct Golden {
  const char* name;
  render::Picture view;
};

class GoldenImage : public ::testing::TestWithParam<std::string> {};

bool read_png(const std::string& path, int& width, int& height, std::vector<uint8_t>& rgba) {
  auto input = OIIO::ImageInput::open(path);
  if (!input) return false;
  width = input->spec().width;
  height = input->spec().height;
  rgba.assign(static_cast<size_t>(width) * static_cast<size_t>(height) * 4, 255);
  return input->read_image(0, 0, 0, std::min(input->spec().nchannels, 4), OIIO::TypeDesc::UINT8, rgba.data(), 4);
}

void write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba) {
  auto output = OIIO::ImageOutput::create(path);
  if (output && output->open(path, OIIO::ImageSpec(width, height, 4, OIIO::TypeDesc::UINT8))) {
    output->write_image(OIIO::TypeDesc::UINT8, rgba.data());
    output->close();
  }
}

TEST_P(GoldenImage, DemoMatchesTheGoldenPictures) {
  for (const Golden golden : {Golden{"demo_color", render::Picture::color}, Golden{"demo_ao", render::Picture::ao}}) {
    render::FrameSettings settings;
    settings.width = 128;
    settings.height = 96;
    settings.output = golden.view;
    settings.check_errors = true;
    test::Harness h;
    ASSERT_TRUE(h.start(GetParam(), "builtin:demo", settings));
    const std::vector<uint8_t> actual = h.renderer.read_color();
    const std::string golden_path = std::string(PLAYER_GOLDEN_DIR) + "/" + golden.name + ".png";
    const std::string out_base = std::string(PLAYER_TEST_OUTPUT_DIR) + "/" + golden.name + "." + GetParam();
    int width = 0, height = 0;
    std::vector<uint8_t> expected;
    if (!read_png(golden_path, width, height, expected)) {
      write_png(out_base + ".actual.png", settings.width, settings.height, actual);
      FAIL() << golden_path << " is missing; the picture rendered now is " << out_base
             << ".actual.png: look at it, then run tools/accept-goldens to make it the golden";
    }
    ASSERT_EQ(width, settings.width);
    ASSERT_EQ(height, settings.height);
    std::vector<uint8_t> diff(actual.size(), 255);
    size_t failing = 0;
    int worst = 0;
    for (size_t p = 0; p < actual.size(); p += 4) {
      int pixel_worst = 0;
      for (size_t c = 0; c < 3; ++c) pixel_worst = std::max(pixel_worst, std::abs(int(actual[p + c]) - int(expected[p + c])));
      worst = std::max(worst, pixel_worst);
      if (pixel_worst > kMaxChannelDifference) ++failing;
      // Diff image: black where equal, brighter red the larger the difference.
      diff[p] = static_cast<uint8_t>(std::min(255, pixel_worst * 16));
      diff[p + 1] = diff[p + 2] = 0;
    }
    const double share = static_cast<double>(failing) / static_cast<double>(actual.size() / 4);
    if (share > kMaxFailingShare) {
      write_png(out_base + ".actual.png", settings.width, settings.height, actual);
      write_png(out_base + ".diff.png", settings.width, settings.height, diff);
    }
    EXPECT_LE(share, kMaxFailingShare) << golden.name << " on " << GetParam() << ": " << failing << " pixels differ by more than "
                                       << kMaxChannelDifference << "/255 (worst " << worst << "); see " << out_base
                                       << ".actual.png and .diff.png";
  }
}

INSTANTIATE_TEST_SUITE_P(Platforms, GoldenImage, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace
