// The dump reader and the aoref command: a synthetic dump written here (no GL needed), and end to end
// on real dumps from `player render --dump`.
#include "aoref/dump.h"
#include "aoref/metrics.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <sys/wait.h>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace aoref {
namespace {

namespace fs = std::filesystem;

struct CommandResult {
  int status = -1;
  std::string output;  // stdout and stderr together
};

CommandResult run(const std::string& command) {
  CommandResult result;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

fs::path fresh_dir(const std::string& name) {
  const fs::path dir = fs::path(AOREF_TEST_OUTPUT_DIR) / ("aoref_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// An 8 x 8 dump of builtin:plane (the square [-1, 1]^2 at z = 0 facing +Z) seen head-on from z = 3;
// the left two columns are background.
nlohmann::json write_synthetic_dump(const fs::path& dir) {
  constexpr int n = 8;
  Image position(n, n, 4), normal(n, n, 4), depth(n, n, 1), ao(n, n, 1);
  for (int y = 0; y < n; ++y)
    for (int x = 2; x < n; ++x) {
      const size_t i = static_cast<size_t>(y * n + x);
      position.at(i, 0) = -0.8f + 0.2f * static_cast<float>(x);
      position.at(i, 1) = 0.7f - 0.2f * static_cast<float>(y);
      position.at(i, 3) = normal.at(i, 3) = 1.0f;
      normal.at(i, 2) = 1.0f;
      depth.at(i) = 3.0f;
      ao.at(i) = 0.5f;
    }
  std::string error;
  EXPECT_TRUE(write_exr((dir / "position.exr").string(), position, {"R", "G", "B", "A"}, error)) << error;
  EXPECT_TRUE(write_exr((dir / "normal.exr").string(), normal, {"R", "G", "B", "A"}, error)) << error;
  EXPECT_TRUE(write_exr((dir / "depth.exr").string(), depth, {"Y"}, error)) << error;
  EXPECT_TRUE(write_exr((dir / "ao_raw.exr").string(), ao, {"Y"}, error)) << error;
  EXPECT_TRUE(write_exr((dir / "ao_blurred.exr").string(), ao, {"Y"}, error)) << error;
  const nlohmann::json identity = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}};
  nlohmann::json doc = {
      {"scene", "builtin:plane"},
      {"width", n},
      {"height", n},
      {"camera", {{"eye", {0, 0, 3}}, {"view", identity}, {"projection", identity}, {"near", 1.0}, {"far", 5.0}}},
      {"ao", {{"samples", 8}, {"radii", {0.2, 0.1}}, {"bias_fraction", 0.03}, {"pattern", "poisson"}, {"blur", "gaussian"}}}};
  std::ofstream(dir / "camera.json") << doc.dump(2);
  return doc;
}

const std::string kAoref = AOREF_CLI;

TEST(Dump, ReadsEveryFieldAndImage) {
  const fs::path dir = fresh_dir("dump_read");
  write_synthetic_dump(dir);
  Dump dump;
  std::string error;
  ASSERT_TRUE(read_dump(dir.string(), dump, error)) << error;
  EXPECT_EQ(dump.scene, "builtin:plane");
  EXPECT_EQ(dump.view.width(), 8);
  EXPECT_EQ(dump.view.radii, (std::vector<double>{0.2, 0.1}));
  EXPECT_EQ(dump.view.eye, glm::dvec3(0, 0, 3));
  EXPECT_FALSE(dump.view.is_object(0));
  EXPECT_TRUE(dump.view.is_object(2));
  EXPECT_FLOAT_EQ(dump.view.position.at(2, 1), 0.7f) << "row 0 is the top row, as written";
  EXPECT_EQ(dump.samples, 8);
}

TEST(Dump, ErrorsNameTheFileAndTheField) {
  const fs::path dir = fresh_dir("dump_errors");
  nlohmann::json doc = write_synthetic_dump(dir);
  Dump dump;
  std::string error;
  const auto expect_error = [&](const std::string& first, const std::string& second) {
    EXPECT_FALSE(read_dump(dir.string(), dump, error));
    EXPECT_NE(error.find(first), std::string::npos) << error;
    EXPECT_NE(error.find(second), std::string::npos) << error;
  };
  nlohmann::json bad = doc;
  bad["ao"]["radii"] = {0.1, 0.2};  // not largest first
  std::ofstream(dir / "camera.json") << bad.dump();
  expect_error("camera.json", "ao.radii: expected a non-empty array of positive finite numbers, largest first");
  bad = doc;
  bad["camera"].erase("eye");
  std::ofstream(dir / "camera.json") << bad.dump();
  expect_error("camera.json", "camera.eye: expected an array of 3 finite numbers, found nothing");
  bad = doc;
  bad["width"] = 9;
  std::ofstream(dir / "camera.json") << bad.dump();
  expect_error("position.exr", "expected 9x8");
  std::ofstream(dir / "camera.json") << "{ not json";
  expect_error("camera.json", "not valid JSON");
  std::ofstream(dir / "camera.json") << doc.dump();
  fs::remove(dir / "normal.exr");
  expect_error("normal.exr", "cannot open");
}

TEST(Cli, WritesReferenceAndNoiseAndComparesOnASyntheticDump) {
  const fs::path dir = fresh_dir("cli_synthetic");
  write_synthetic_dump(dir);
  const fs::path out = dir / "ref.exr";
  const CommandResult r =
      run(kAoref + " --dump " + dir.string() + " --rays 64 -o " + out.string() + " --compare " + (dir / "ao_raw.exr").string());
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("noise: binomial standard error per pixel max"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("MAE"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("SSIM"), std::string::npos) << r.output;
  const fs::path map = dir / "error.png";
  const CommandResult mapped = run(kAoref + " --dump " + dir.string() + " --rays 64 -o " + out.string() + " --compare " +
                                   (dir / "ao_raw.exr").string() + " --error-map " + map.string() + " --error-scale 0.5");
  ASSERT_EQ(mapped.status, 0) << mapped.output;
  EXPECT_NE(mapped.output.find("wrote " + map.string() + " (estimate - reference, +-0.5 in full colour)"), std::string::npos)
      << mapped.output;
  // Both files are images of the dump's 8x8 with the channels each is written with.
  const auto read_dump_sized = [](const fs::path& path, int channels, Image& image) {
    std::string error;
    if (!read_image(path.string(), image, error)) {
      ADD_FAILURE() << error;
      return false;
    }
    EXPECT_EQ(image.width, 8) << path;
    EXPECT_EQ(image.height, 8) << path;
    EXPECT_EQ(image.channels, channels) << path;
    return image.width == 8 && image.height == 8 && image.channels == channels;
  };
  Image map_image, image;
  EXPECT_TRUE(read_dump_sized(map, 3, map_image));
  ASSERT_TRUE(read_dump_sized(out, 2, image));
  EXPECT_EQ(image.at(0, 0), 0.0f) << "background";
  // A plane: half of each shell is behind it (see reference_test); SE of 64 rays is 1/16.
  EXPECT_NEAR(image.at(2, 0), 0.5f, 5.0 / 16.0);
  EXPECT_NEAR(image.at(2, 1), std::sqrt(image.at(2, 0) * (1.0 - image.at(2, 0)) / 64.0), 1e-6);
}

TEST(Cli, FailsCleanlyOnBadInput) {
  const fs::path dir = fresh_dir("cli_errors");
  write_synthetic_dump(dir);
  const std::string out = " -o " + (dir / "x.exr").string();
  struct Case {
    std::string arguments, message;
  };
  const Case cases[] = {
      {"--dump " + (dir / "missing").string() + out, "camera.json: cannot open"},
      {"--dump " + dir.string() + " --scene builtin:nope" + out, "builtin:nope"},
      {"--dump " + dir.string() + " --radius 0.5" + out, "--radius: applies to --reference near-field only"},
      {"--dump " + dir.string() + " --rays 0" + out, "--rays"},
      {"--dump " + dir.string() + " --reference cone" + out, "--reference"},
      {"--dump " + dir.string() + " --compare " + (dir / "nope.exr").string() + out, "nope.exr"},
      {"--dump " + dir.string() + " -o /nonexistent-folder/x.exr", "/nonexistent-folder/x.exr"},
      {"--dump " + dir.string() + " --error-map " + (dir / "e.png").string() + out, "--error-map: needs --compare"},
  };
  for (const Case& c : cases) {
    const CommandResult r = run(kAoref + " " + c.arguments);
    EXPECT_NE(r.status, 0) << c.arguments << "\n" << r.output;
    EXPECT_NE(r.output.find(c.message), std::string::npos) << c.arguments << "\n" << r.output;
  }
  const CommandResult help = run(kAoref + " --help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.output.find("--reference"), std::string::npos);
}

// End to end: the player's dump of a scene, traced by aoref; returns the reference and the dump.
void player_dump_and_reference(const std::string& name, const std::string& player_arguments, const std::string& reference,
                               Dump& dump, Image& out) {
  const fs::path dir = fresh_dir("e2e_" + name);
  // The paper's sphere estimator (8 samples x 5 radii), whatever the player's default is.
  const CommandResult render =
      run(std::string(PLAYER_BIN) + " render " + player_arguments + " --estimator sphere --samples 8 --radii 5 --size 48x48 -o " +
          (dir / "frame.png").string() + " --dump " + (dir / "dump").string());
  ASSERT_EQ(render.status, 0) << render.output;
  const CommandResult r = run(kAoref + " --dump " + (dir / "dump").string() + " --reference " + reference + " --rays 128 -o " +
                              (dir / "ref.exr").string() + " --compare " + (dir / "dump" / "ao_raw.exr").string());
  ASSERT_EQ(r.status, 0) << r.output;
  std::string error;
  ASSERT_TRUE(read_dump((dir / "dump").string(), dump, error)) << error;
  ASSERT_TRUE(read_image((dir / "ref.exr").string(), out, error)) << error;
  ASSERT_EQ(out.width, 48);
  ASSERT_EQ(out.height, 48);
  ASSERT_EQ(out.channels, 2);
  for (size_t i = 0; i < out.pixel_count(); ++i) {
    ASSERT_GE(out.at(i, 0), 0.0f);
    ASSERT_LE(out.at(i, 0), 1.0f);
    ASSERT_LE(out.at(i, 1), 0.5f / std::sqrt(128.0f) + 1e-6f) << "SE is at most 1/(2 sqrt N)";
    if (!dump.view.is_object(i)) {
      ASSERT_EQ(out.at(i, 0), 0.0f) << "background is 0";
    }
  }
}

Image channel(const Image& image, int c) {
  Image one(image.width, image.height, 1);
  for (size_t i = 0; i < one.pixel_count(); ++i) one.at(i) = image.at(i, c);
  return one;
}

TEST(EndToEnd, CornerEstimateIsCloseToTheSphereReference) {
  Dump dump;
  Image out;
  ASSERT_NO_FATAL_FAILURE(player_dump_and_reference("corner", "builtin:corner", "sphere", dump, out));
  const Metrics m = compare(dump.ao_raw, channel(out, 0), dump.depth);
  ASSERT_GT(m.pixels, 500u);
  EXPECT_TRUE(std::isfinite(m.mae) && std::isfinite(m.rmse) && std::isfinite(m.ssim));
  // The estimator approximates this reference with 8 samples per radius, a depth bias and a range
  // check; measured MAE is about 0.02 at 48x48. 0.1 flags a broken reference or a mismatched frame
  // (flipped rows, wrong eye) while leaving room for the estimator's own error.
  EXPECT_LT(m.mae, 0.1);
  // The near-field reference of an open corner is far below the sphere estimator's 0.5 floor level.
  Dump near_dump;
  Image near_out;
  ASSERT_NO_FATAL_FAILURE(player_dump_and_reference("corner_near", "builtin:corner", "near-field", near_dump, near_out));
  const Metrics near = compare(near_dump.ao_raw, channel(near_out, 0), near_dump.depth);
  EXPECT_GT(near.bias, 0.3) << "the sphere estimator counts the half-space behind every plane";
}

TEST(EndToEnd, PlaneEstimateAgreesWithTheSphereReference) {
  Dump dump;
  Image out;
  ASSERT_NO_FATAL_FAILURE(player_dump_and_reference("plane", "builtin:plane --azimuth 0 --elevation 0", "sphere", dump, out));
  // Interior pixels of the square (its silhouette lets samples fall off the plane): both near 1/2.
  double estimate = 0.0, reference = 0.0;
  int n = 0;
  for (int y = 18; y < 30; ++y)
    for (int x = 18; x < 30; ++x, ++n) {
      const size_t i = static_cast<size_t>(y * 48 + x);
      ASSERT_TRUE(dump.view.is_object(i));
      estimate += dump.ao_raw.at(i);
      reference += out.at(i, 0);
    }
  EXPECT_NEAR(reference / n, 0.5, 0.02);
  // The player's 8-sample kernel quantises in steps of 1/8 and its bias drops samples just behind the
  // plane: one sample's worth.
  EXPECT_NEAR(estimate / n, reference / n, 1.0 / 8.0);
}

}  // namespace
}  // namespace aoref
