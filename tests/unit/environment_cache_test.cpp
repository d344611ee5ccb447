// Prepared environments kept between runs: read back exactly, never for other pixels or sizes,
// prepared again when the file is damaged, and nothing kept without a folder.
#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "scene/environment.h"

namespace fs = std::filesystem;

namespace {

class KeptEnvironments : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("environment-cache-test-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    scene::keep_prepared_environments(dir_);
    before_ = scene::environment_cache_counts();
  }
  void TearDown() override {
    scene::keep_prepared_environments({});
    fs::remove_all(dir_);
  }

  // A small image with a bright patch, so that every level differs from its neighbours.
  static std::vector<float> image(float bright = 6.0f) {
    std::vector<float> rgb(std::size_t(kWidth) * kHeight * 3, 0.2f);
    for (int y = 2; y < 5; ++y)
      for (int x = 3; x < 9; ++x) rgb[(std::size_t(y) * kWidth + x) * 3 + 1] = bright;
    return rgb;
  }
  static scene::Environment prepare(const std::vector<float>& rgb, int face_size = 16, int levels = 4) {
    return scene::prepare_environment("test", kWidth, kHeight, rgb, face_size, levels);
  }
  // What this test has done so far: prepared, loaded, rejected.
  std::vector<std::size_t> counts() const {
    const scene::EnvironmentCacheCounts now = scene::environment_cache_counts();
    return {now.prepared - before_.prepared, now.loaded - before_.loaded, now.rejected - before_.rejected};
  }
  std::vector<fs::path> files() const {
    std::vector<fs::path> found;
    for (const auto& entry : fs::directory_iterator(dir_)) found.push_back(entry.path());
    return found;
  }
  static void expect_same(const scene::Environment& a, const scene::Environment& b) {
    EXPECT_EQ(a.face_size, b.face_size);
    EXPECT_EQ(a.irradiance_sh, b.irradiance_sh);
    EXPECT_EQ(a.specular, b.specular);  // bit for bit: floats read back as written
  }

  static constexpr int kWidth = 16, kHeight = 8;
  fs::path dir_;
  scene::EnvironmentCacheCounts before_;
};

TEST_F(KeptEnvironments, ASecondPreparationReadsTheFirstBackExactly) {
  const scene::Environment first = prepare(image());
  EXPECT_EQ(counts(), (std::vector<std::size_t>{1, 0, 0}));
  ASSERT_EQ(files().size(), 1u);
  EXPECT_EQ(files()[0].extension(), ".env");
  const scene::Environment second = scene::prepare_environment("another name", kWidth, kHeight, image(), 16, 4);
  EXPECT_EQ(counts(), (std::vector<std::size_t>{1, 1, 0}));
  expect_same(first, second);
  EXPECT_EQ(second.name, "another name");
  EXPECT_EQ(scene::environment_cache_counts().dir, dir_);
}

TEST_F(KeptEnvironments, OtherPixelsOrSizesArePreparedAndKeptApart) {
  const scene::Environment base = prepare(image());
  const scene::Environment brighter = prepare(image(7.0f));
  const scene::Environment larger = prepare(image(), 32, 4);
  const scene::Environment fewer_levels = prepare(image(), 16, 3);
  EXPECT_EQ(counts(), (std::vector<std::size_t>{4, 0, 0}));
  EXPECT_EQ(files().size(), 4u);
  EXPECT_NE(base.specular, brighter.specular);
  EXPECT_EQ(larger.face_size, 32);
  EXPECT_EQ(fewer_levels.levels(), 3);
  expect_same(prepare(image(7.0f)), brighter);
  expect_same(prepare(image(), 16, 3), fewer_levels);
  EXPECT_EQ(counts(), (std::vector<std::size_t>{4, 2, 0}));
}

TEST_F(KeptEnvironments, ADamagedOrTruncatedFileIsPreparedAgainAndReplaced) {
  const scene::Environment reference = prepare(image());
  ASSERT_EQ(files().size(), 1u);
  const fs::path file = files()[0];
  const auto size = fs::file_size(file);
  {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekg(static_cast<std::streamoff>(size / 2));
    const char byte = static_cast<char>(f.get());
    f.seekp(static_cast<std::streamoff>(size / 2));
    f.put(static_cast<char>(byte ^ 0x5a));  // inside a level's floats: only the checksum notices
  }
  expect_same(prepare(image()), reference);
  EXPECT_EQ(counts(), (std::vector<std::size_t>{2, 0, 1}));
  EXPECT_EQ(fs::file_size(file), size);  // written again, whole
  expect_same(prepare(image()), reference);
  EXPECT_EQ(counts(), (std::vector<std::size_t>{2, 1, 1}));

  fs::resize_file(file, size - 4);
  expect_same(prepare(image()), reference);
  EXPECT_EQ(counts(), (std::vector<std::size_t>{3, 1, 2}));
  fs::resize_file(file, 0);
  expect_same(prepare(image()), reference);
  EXPECT_EQ(counts(), (std::vector<std::size_t>{4, 1, 3}));
}

TEST_F(KeptEnvironments, WithoutAFolderNothingIsKeptOrRead) {
  scene::keep_prepared_environments({});
  prepare(image());
  prepare(image());
  EXPECT_EQ(counts(), (std::vector<std::size_t>{2, 0, 0}));
  EXPECT_FALSE(fs::exists(dir_));
  EXPECT_TRUE(scene::environment_cache_counts().dir.empty());
}

TEST_F(KeptEnvironments, AFolderThatCannotBeMadeCostsOnlyTheWorkAndSaysWhy) {
  fs::create_directories(dir_);
  std::ofstream(dir_ / "a-file") << "not a folder";
  scene::keep_prepared_environments(dir_ / "a-file" / "environments");
  const scene::Environment env = prepare(image());
  EXPECT_EQ(env.levels(), 4);
  EXPECT_EQ(counts(), (std::vector<std::size_t>{1, 0, 0}));
  EXPECT_NE(scene::environment_cache_counts().problem.find("cannot make " + (dir_ / "a-file" / "environments").string()),
            std::string::npos)
      << scene::environment_cache_counts().problem;
}

TEST_F(KeptEnvironments, NamingTheFolderKeepsTheMostRecentlyUsedWithinTheLimit) {
  std::vector<fs::path> made;
  for (std::size_t i = 0; i < scene::kMaxKeptEnvironments + 2; ++i) {
    prepare(image(1.0f + static_cast<float>(i)), 4, 1);
    for (const fs::path& f : files())
      if (std::find(made.begin(), made.end(), f) == made.end()) made.push_back(f);
    // Distinct modification times, oldest first, whatever the file system's clock resolution.
    fs::last_write_time(made.back(), fs::file_time_type::clock::now() - std::chrono::hours(100) + std::chrono::minutes(i));
  }
  ASSERT_EQ(made.size(), scene::kMaxKeptEnvironments + 2);
  scene::keep_prepared_environments(dir_);
  EXPECT_EQ(files().size(), scene::kMaxKeptEnvironments);
  EXPECT_FALSE(fs::exists(made[0]));
  EXPECT_FALSE(fs::exists(made[1]));
  EXPECT_TRUE(fs::exists(made[2]));
  EXPECT_TRUE(fs::exists(made.back()));
}

}  // namespace
