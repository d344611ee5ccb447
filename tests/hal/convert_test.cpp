// YUYV and MJPEG to RGB against known values.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>

#include "hal/convert.h"

namespace hal {
namespace {

// BT.601 limited-range reference colours (Y, U, V) -> RGB, as printed in colour-bar tables.
struct YuvCase {
  std::uint8_t y, u, v;
  std::uint8_t r, g, b;
};
constexpr YuvCase kBars[] = {
    {16, 128, 128, 0, 0, 0},     {235, 128, 128, 255, 255, 255}, {126, 128, 128, 128, 128, 128},
    {81, 90, 240, 255, 0, 0},    {145, 54, 34, 0, 255, 0},       {41, 240, 110, 0, 0, 255},
    {210, 16, 146, 255, 255, 0}, {170, 166, 16, 0, 255, 255},    {106, 202, 222, 255, 0, 255},
};

TEST(Convert, YuyvColourBars) {
  for (const auto& c : kBars) {
    // Two pixels sharing chroma, on a row padded to a wider stride as drivers do.
    const std::uint8_t row[8] = {c.y, c.u, c.y, c.v, 0xEE, 0xEE, 0xEE, 0xEE};
    RgbImage out(2, 1);
    yuyv_to_rgb(row, 2, 1, 8, out);
    for (int px = 0; px < 2; ++px) {
      // 1 level: the published bar values are themselves rounded.
      EXPECT_NEAR(out.at(px, 0)[0], c.r, 1) << int(c.y) << "," << int(c.u) << "," << int(c.v);
      EXPECT_NEAR(out.at(px, 0)[1], c.g, 1) << int(c.y) << "," << int(c.u) << "," << int(c.v);
      EXPECT_NEAR(out.at(px, 0)[2], c.b, 1) << int(c.y) << "," << int(c.u) << "," << int(c.v);
    }
  }
}

TEST(Convert, YuyvUsesEachPixelsOwnLumaAndRespectsStride) {
  const std::uint8_t src[] = {16,  128, 235, 128, 0, 0,  // row 0: black, white, padding
                              235, 128, 16,  128, 0, 0};
  RgbImage out(2, 2);
  yuyv_to_rgb(src, 2, 2, 6, out);
  EXPECT_EQ(out.at(0, 0)[1], 0);
  EXPECT_EQ(out.at(1, 0)[1], 255);
  EXPECT_EQ(out.at(0, 1)[1], 255);
  EXPECT_EQ(out.at(1, 1)[1], 0);
}

// Found by tests/fuzz (yuyv): with an odd width and bytesperline = width * 2 (what the camera
// raises a smaller one to), the last pixel read the V byte past the end of the frame. The file is
// the fuzz target's input: 5 bytes of format (3 x 3, bytesperline 0), then the frame.
TEST(Convert, YuyvOddWidthLastPixelStaysInsideTheRowAndTakesItsNeighboursChroma) {
  const std::string path = std::string(HAL_SOURCE_DIR) + "/tests/fuzz/regressions/yuyv/odd_width_tight_stride.yuyv";
  std::ifstream in(path, std::ios::binary);
  ASSERT_TRUE(in) << path;
  const std::vector<std::uint8_t> file((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const int width = 3, height = 3, stride = 6;
  ASSERT_EQ(file.size(), 5u + stride * height);
  // Exactly the frame's bytes on the heap, so ASan (asan preset) flags a read past its end.
  const std::vector<std::uint8_t> frame(file.begin() + 5, file.end());
  RgbImage out(width, height);
  yuyv_to_rgb(frame, width, height, stride, out);
  for (int y = 0; y < height; ++y) {
    const std::uint8_t* row = frame.data() + y * stride;
    const std::uint8_t pair[4] = {row[4], row[1], row[4], row[3]};  // Y2 with the first pair's U and V
    RgbImage expected(2, 1);
    yuyv_to_rgb(pair, 2, 1, 4, expected);
    for (int c = 0; c < 3; ++c) EXPECT_EQ(out.at(2, y)[c], expected.at(0, 0)[c]) << "row " << y << " channel " << c;
  }
  RgbImage one(1, 1);
  const std::vector<std::uint8_t> single = {235, 16};  // Y, U: a 1-pixel row has no V, so no chroma
  yuyv_to_rgb(single, 1, 1, 2, one);
  EXPECT_EQ(one.at(0, 0)[0], 255);
  EXPECT_EQ(one.at(0, 0)[1], 255);
  EXPECT_EQ(one.at(0, 0)[2], 255);
}

std::vector<std::uint8_t> encode_jpeg(const RgbImage& img) {
  std::vector<std::uint8_t> bytes;
  OIIO::Filesystem::IOVecOutput sink(bytes);
  auto out = OIIO::ImageOutput::create("jpg");
  out->set_ioproxy(&sink);
  OIIO::ImageSpec spec(img.width, img.height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("Compression", "jpeg:95");
  EXPECT_TRUE(out->open("test.jpg", spec));
  EXPECT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, img.pixels.data()));
  out->close();
  return bytes;
}

// Many UVC cameras send MJPEG without Huffman tables (DHT) and rely on the standard ones.
std::vector<std::uint8_t> strip_huffman_tables(const std::vector<std::uint8_t>& jpeg) {
  std::vector<std::uint8_t> out(jpeg.begin(), jpeg.begin() + 2);
  std::size_t i = 2;
  while (i + 4 <= jpeg.size()) {
    if (jpeg[i + 1] == 0xDA) {  // start of scan: entropy-coded data follows
      out.insert(out.end(), jpeg.begin() + static_cast<long>(i), jpeg.end());
      break;
    }
    const std::size_t len = 2 + ((jpeg[i + 2] << 8) | jpeg[i + 3]);
    if (jpeg[i + 1] != 0xC4)
      out.insert(out.end(), jpeg.begin() + static_cast<long>(i), jpeg.begin() + static_cast<long>(i + len));
    i += len;
  }
  return out;
}

// Four flat 16x16 quadrants: known colours away from JPEG's block edges.
RgbImage quadrants() {
  RgbImage img(32, 32);
  const std::uint8_t colours[4][3] = {{220, 30, 40}, {20, 200, 60}, {30, 50, 210}, {128, 128, 128}};
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      for (int c = 0; c < 3; ++c) img.at(x, y)[c] = colours[(y / 16) * 2 + x / 16][c];
  return img;
}

void expect_quadrants(const RgbImage& out) {
  const RgbImage ref = quadrants();
  for (int y : {4, 11, 20, 27})
    for (int x : {4, 11, 20, 27})
      for (int c = 0; c < 3; ++c)
        // 6 levels: chroma is subsampled and quantised at quality 95.
        EXPECT_NEAR(out.at(x, y)[c], ref.at(x, y)[c], 6) << x << "," << y << " channel " << c;
}

TEST(Convert, MjpegDecodesKnownColours) {
  const auto jpeg = encode_jpeg(quadrants());
  MjpegDecoder dec;
  RgbImage out(32, 32);
  std::string err;
  ASSERT_TRUE(dec.decode(jpeg, out, &err)) << err;
  expect_quadrants(out);
  // The decoder is reused frame after frame.
  ASSERT_TRUE(dec.decode(jpeg, out, &err)) << err;
  expect_quadrants(out);
}

TEST(Convert, MjpegWithoutHuffmanTablesDecodes) {
  const auto full = encode_jpeg(quadrants());
  const auto stripped = strip_huffman_tables(full);
  ASSERT_LT(stripped.size(), full.size());
  MjpegDecoder dec;
  RgbImage out(32, 32);
  std::string err;
  ASSERT_TRUE(dec.decode(stripped, out, &err)) << err;
  expect_quadrants(out);
}

TEST(Convert, MjpegErrorsSayWhatWasWrong) {
  MjpegDecoder dec;
  RgbImage out(16, 16);
  std::string err;
  const auto jpeg = encode_jpeg(quadrants());
  EXPECT_FALSE(dec.decode(jpeg, out, &err));
  EXPECT_EQ(err, "MJPEG frame: expected 16x16, got 32x32");
  const std::vector<std::uint8_t> garbage(100, 0x42);
  EXPECT_FALSE(dec.decode(garbage, out, &err));
  EXPECT_NE(err.find("MJPEG frame"), std::string::npos);
  // Still usable after errors.
  RgbImage ok(32, 32);
  EXPECT_TRUE(dec.decode(jpeg, ok, &err)) << err;
}

// The size a frame declares is checked before the decoder sees it: libjpeg allocates by it, and a
// corrupt frame declaring 65535x65535 asked for 4.4 GB (fuzz finding, tests/fuzz/regressions/mjpeg).
// The check walks the marker segments, so a SOF marker inside an APP segment's payload (Exif) is
// not taken for the frame's.
TEST(Convert, MjpegRefusesADeclaredSizeBeforeDecoding) {
  auto jpeg = encode_jpeg(quadrants());
  std::size_t sof = 0;
  for (std::size_t i = 2; i + 1 < jpeg.size(); ++i)
    if (jpeg[i] == 0xFF && jpeg[i + 1] == 0xC0) {
      sof = i;
      break;
    }
  ASSERT_GT(sof, 0u);
  auto huge = jpeg;
  huge[sof + 5] = huge[sof + 6] = huge[sof + 7] = huge[sof + 8] = 0xFF;  // 65535 x 65535
  MjpegDecoder dec;
  RgbImage out(32, 32);
  std::string err;
  EXPECT_FALSE(dec.decode(huge, out, &err));
  EXPECT_EQ(err, "MJPEG frame: expected 32x32, got 65535x65535");
  // An APP1 segment right after SOI whose payload holds a fake SOF0 declaring 32x32.
  const std::vector<std::uint8_t> app1 = {0xFF, 0xE1, 0x00, 0x0D, 'E', 'x', 'i', 'f', 0xFF, 0xC0, 0x00, 0x11, 0x08, 0x00, 0x20};
  auto disguised = huge;
  disguised.insert(disguised.begin() + 2, app1.begin(), app1.end());
  EXPECT_FALSE(dec.decode(disguised, out, &err));
  EXPECT_EQ(err, "MJPEG frame: expected 32x32, got 65535x65535");
  auto with_app1 = jpeg;
  with_app1.insert(with_app1.begin() + 2, app1.begin(), app1.end());
  EXPECT_TRUE(dec.decode(with_app1, out, &err)) << err;
  expect_quadrants(out);
  // Cut inside a segment, or before any frame header.
  const std::vector<std::uint8_t> cut(jpeg.begin(), jpeg.begin() + static_cast<std::ptrdiff_t>(sof + 4));
  EXPECT_FALSE(dec.decode(cut, out, &err));
  EXPECT_EQ(err, "MJPEG frame: not a decodable JPEG: a segment runs past the end of the frame");
  const std::vector<std::uint8_t> no_frame = {0xFF, 0xD8, 0xFF, 0xDA, 0x00, 0x02, 0xFF, 0xD9};
  EXPECT_FALSE(dec.decode(no_frame, out, &err));
  EXPECT_EQ(err, "MJPEG frame: not a decodable JPEG: no frame header before the image data");
}

}  // namespace
}  // namespace hal
