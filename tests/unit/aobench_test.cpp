// The benchmark's configuration language and Pareto front.
#include "chart.h"
#include "configs.h"
#include "render/settings.h"

#include <gtest/gtest.h>

#include <algorithm>
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
  render::FrameSettings player;
  EXPECT_FALSE(fallback->settings.reuse_static_ao);  // every frame computes the AO it times
  player.reuse_static_ao = false;
  EXPECT_EQ(aobench::describe(fallback->settings), aobench::describe(player));
}

TEST(AobenchConfigs, SpecificationsRoundTripThroughDescribe) {
  std::string error;
  const auto config = aobench::parse_config("estimator=horizon,samples=32,radii=3,pattern=latin,blur=bilateral,resolution=half,depth-chain=off,skip-radii=off", error);
  ASSERT_TRUE(config.has_value()) << error;
  const auto again = aobench::parse_config(aobench::describe(config->settings), error);
  ASSERT_TRUE(again.has_value()) << error;
  EXPECT_EQ(aobench::describe(again->settings), aobench::describe(config->settings));
  EXPECT_EQ(config->settings.ao_settings.samples, 32);
  EXPECT_TRUE(config->settings.ao_settings.half_resolution);
}

TEST(AobenchConfigs, SavingsCanBeSwitchedOffOneByOne) {
  std::string error;
  const auto config = aobench::parse_config("skip-background=off,untextured-variant=off,reuse-ao=on,prepass=off", error);
  ASSERT_TRUE(config.has_value()) << error;
  EXPECT_FALSE(config->settings.ao_settings.skip_background);
  EXPECT_FALSE(config->settings.untextured_variant);
  EXPECT_TRUE(config->settings.reuse_static_ao);
  EXPECT_EQ(config->settings.prepass, render::Prepass::off);
  EXPECT_EQ(aobench::describe(config->settings),
            aobench::describe(aobench::parse_config(aobench::describe(config->settings), error)->settings));
  // Settings left at the player's default stay out of the name.
  EXPECT_EQ(aobench::describe(aobench::parse_config("default", error)->settings).find("background"), std::string::npos);
  EXPECT_FALSE(aobench::parse_config("skip-background=maybe", error).has_value());
  EXPECT_NE(error.find("skip-background: expected on|off, got 'maybe'"), std::string::npos) << error;
  EXPECT_FALSE(aobench::parse_config("prepass=sometimes", error).has_value());
}

TEST(AobenchConfigs, AblationTurnsOffOneSavingAtATime) {
  const auto configs = aobench::sweep("ablation");
  ASSERT_FALSE(configs.empty());
  EXPECT_EQ(configs.front().name, "default");
  const render::FrameSettings player;
  for (const aobench::Config& config : configs) {
    const auto& s = config.settings;
    // Each differs from the default in the one respect its name says and nowhere else.
    int differences = (s.ao_settings.skip_background != player.ao_settings.skip_background) +
                      (s.untextured_variant != player.untextured_variant) + (s.reuse_static_ao ? 1 : 0) +
                      (s.prepass != player.prepass) + (s.ao_settings.depth_chain != player.ao_settings.depth_chain) +
                      (s.ao_settings.half_resolution != player.ao_settings.half_resolution) +
                      (s.ao_settings.skip_radii != player.ao_settings.skip_radii);
    if (s.ao_settings.radii != player.ao_settings.radii) {
      EXPECT_EQ(s.ao_settings.radii, 5) << config.name;
    }
    EXPECT_LE(differences, 1) << config.name;
  }
  for (const char* saving : {"skip-background=off", "untextured-variant=off", "reuse-ao=on", "prepass=on", "radii=5,skip-radii=off"})
    EXPECT_TRUE(std::any_of(configs.begin(), configs.end(), [&](const aobench::Config& c) { return c.name == saving; })) << saving;
}

TEST(AobenchConfigs, BadSpecificationsSayWhatIsWrong) {
  std::string error;
  EXPECT_FALSE(aobench::parse_config("samples=0", error).has_value());
  EXPECT_NE(error.find("samples: expected 1..64, got '0'"), std::string::npos) << error;
  EXPECT_FALSE(aobench::parse_config("estimator=ray", error).has_value());
  EXPECT_NE(error.find("estimator"), std::string::npos);
  EXPECT_FALSE(aobench::parse_config("colour=red", error).has_value());
  EXPECT_NE(error.find("unknown setting 'colour'"), std::string::npos) << error;
  EXPECT_FALSE(aobench::parse_config("fast", error).has_value());
  EXPECT_NE(error.find("not key=value"), std::string::npos);
}

// The command line, playlists and aobench share one codec; every key reads back what it was given.
TEST(SettingsCodec, EveryKeyRoundTripsItsDefault) {
  const render::FrameSettings defaults;
  for (const render::SettingKey& key : render::setting_keys()) {
    render::FrameSettings settings;
    std::string error;
    const std::string value = render::setting_value(defaults, key.key);
    EXPECT_TRUE(render::apply_setting(settings, key.key, value, error)) << key.key << ": " << error;
    EXPECT_EQ(render::describe(settings, defaults), "") << key.key;
    EXPECT_FALSE(key.choices.empty()) << key.key;
  }
  render::FrameSettings settings;
  std::string error;
  ASSERT_TRUE(render::apply_settings(settings, "estimator=sphere,view=ao,radius=0.25,ao=off", error)) << error;
  EXPECT_EQ(settings.ao_settings.estimator, ssao::Estimator::sphere);
  EXPECT_EQ(settings.output, render::Output::ao);
  EXPECT_FLOAT_EQ(settings.radius, 0.25f);
  EXPECT_FALSE(settings.ao);
  EXPECT_EQ(render::describe(settings, defaults), "ao=off,estimator=sphere,radius=0.25,view=ao");
  // Enum choices come from the enum's name table.
  EXPECT_FALSE(render::apply_setting(settings, "estimator", "ray", error));
  EXPECT_EQ(error, "estimator: expected sphere|hemisphere|horizon, got 'ray'");
  EXPECT_FALSE(render::apply_setting(settings, "radius", "-1", error));
  EXPECT_EQ(error, "radius: expected a number >= 0, got '-1'");
  EXPECT_EQ(settings.radius, 0.25f);  // a refused value changes nothing
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
