// The benchmark's configuration language and Pareto front.
#include "chart.h"
#include "configs.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace {

TEST(AobenchConfigs, NamedConfigurationsAreThePapersAndThePlayersDefault) {
  std::string error;
  const auto paper = aobench::parse_config("paper", error);
  ASSERT_TRUE(paper.has_value()) << error;
  EXPECT_EQ(paper->settings.ao_settings.estimator, ssao::Estimator::sphere);
  EXPECT_EQ(paper->settings.ao_settings.samples, 8);
  EXPECT_EQ(paper->settings.ao_settings.radii, 5);
  EXPECT_EQ(paper->settings.blur.mode, ssao::Blur::gaussian);
  EXPECT_FALSE(paper->settings.ao_settings.skip_radii);
  const auto fallback = aobench::parse_config("default", error);
  ASSERT_TRUE(fallback.has_value());
  const render::FrameSettings player;
  EXPECT_EQ(aobench::describe(fallback->settings), aobench::describe(player));
  EXPECT_FALSE(fallback->settings.reuse_static_ao);  // every frame is timed
}

TEST(AobenchConfigs, SpecificationsRoundTripThroughDescribe) {
  std::string error;
  const auto config = aobench::parse_config("estimator=horizon,samples=32,radii=3,pattern=latin,blur=bilateral,scale=half,chain=off,skip=off", error);
  ASSERT_TRUE(config.has_value()) << error;
  const auto again = aobench::parse_config(aobench::describe(config->settings), error);
  ASSERT_TRUE(again.has_value()) << error;
  EXPECT_EQ(aobench::describe(again->settings), aobench::describe(config->settings));
  EXPECT_EQ(config->settings.ao_settings.samples, 32);
  EXPECT_TRUE(config->settings.ao_settings.half_resolution);
}

TEST(AobenchConfigs, BadSpecificationsSayWhatIsWrong) {
  std::string error;
  EXPECT_FALSE(aobench::parse_config("samples=0", error).has_value());
  EXPECT_NE(error.find("'0' is not a valid samples"), std::string::npos) << error;
  EXPECT_FALSE(aobench::parse_config("estimator=ray", error).has_value());
  EXPECT_NE(error.find("estimator"), std::string::npos);
  EXPECT_FALSE(aobench::parse_config("colour=red", error).has_value());
  EXPECT_NE(error.find("unknown key 'colour'"), std::string::npos);
  EXPECT_FALSE(aobench::parse_config("fast", error).has_value());
  EXPECT_NE(error.find("not key=value"), std::string::npos);
}

TEST(AobenchConfigs, SweepsCoverTheGrid) {
  // quick: 3 estimators x 4 sample counts x 3 radii x 3 blurs x 2 scales, plus 4 patterns at the paper's point.
  EXPECT_EQ(aobench::sweep("quick").size(), 3u * 4 * 3 * 3 * 2 + 4);
  EXPECT_EQ(aobench::sweep("full").size(), 3u * 6 * 5 * 4 * 3 * 2);
}

TEST(AobenchChart, ParetoFrontKeepsOnlyUnbeatenPoints) {
  std::vector<aobench::ChartPoint> points = {
      {10, 0.5, false, ""}, {20, 0.2, false, ""}, {15, 0.6, false, ""}, {30, 0.2, false, ""}, {40, 0.1, false, ""}, {10, 0.5, false, ""}};
  // (15, 0.6) is beaten by (10, 0.5); (30, 0.2) by (20, 0.2); the second (10, 0.5) ties the first.
  EXPECT_EQ(aobench::pareto_front(points), (std::vector<size_t>{0, 1, 4}));
  const std::string path = (std::filesystem::temp_directory_path() / "aobench_chart_test.png").string();
  std::string error;
  EXPECT_TRUE(aobench::write_chart(path, points, "test", "MAE", error)) << error;
  EXPECT_GT(std::filesystem::file_size(path), 1000u);
  std::filesystem::remove(path);
}

}  // namespace
