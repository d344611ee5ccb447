// The benchmark's configuration language and Pareto front.
#include "chart.h"
#include "configs.h"
#include "render/settings.h"

#include <OpenImageIO/imagebuf.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
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
  EXPECT_FALSE(fallback->settings.temporal);         // and that frame's own AO, not an average
  player.reuse_static_ao = false;
  player.temporal = false;
  EXPECT_EQ(aobench::describe(fallback->settings), aobench::describe(player));
}

// Every core key given, in describe()'s order, so the expected text is written out here rather
// than taken from describe() itself: a key dropped, renamed, reordered or mangled shows.
TEST(AobenchConfigs, SpecificationsRoundTripThroughDescribe) {
  const std::string spec =
      "estimator=horizon,samples=32,radii=3,pattern=latin,blur=bilateral,resolution=half,depth-chain=on,skip-radii=off";
  std::string error;
  const auto config = aobench::parse_config(spec, error);
  ASSERT_TRUE(config.has_value()) << error;
  EXPECT_EQ(config->name, spec);
  const ssao::AoSettings& ao = config->settings.ao_settings;
  EXPECT_EQ(ao.estimator, ssao::Estimator::horizon);
  EXPECT_EQ(ao.samples, 32);
  EXPECT_EQ(ao.radii, 3);
  EXPECT_EQ(ao.pattern, ssao::Pattern::latin);
  EXPECT_EQ(config->settings.blur.mode, ssao::Blur::bilateral);
  EXPECT_TRUE(ao.half_resolution);
  EXPECT_TRUE(ao.depth_chain);
  EXPECT_FALSE(ao.skip_radii);
  EXPECT_EQ(aobench::describe(config->settings), spec);
  // Read back: the same settings, field by field, not just the same text.
  const auto again = aobench::parse_config(aobench::describe(config->settings), error);
  ASSERT_TRUE(again.has_value()) << error;
  const ssao::AoSettings& back = again->settings.ao_settings;
  EXPECT_EQ(back.estimator, ao.estimator);
  EXPECT_EQ(back.samples, ao.samples);
  EXPECT_EQ(back.radii, ao.radii);
  EXPECT_EQ(back.pattern, ao.pattern);
  EXPECT_EQ(again->settings.blur.mode, config->settings.blur.mode);
  EXPECT_EQ(back.half_resolution, ao.half_resolution);
  EXPECT_EQ(back.depth_chain, ao.depth_chain);
  EXPECT_EQ(back.skip_radii, ao.skip_radii);
  // The other values of each core key, in the same places.
  const std::string other =
      "estimator=sphere,samples=7,radii=5,pattern=poisson,blur=gaussian,resolution=full,depth-chain=off,skip-radii=on";
  const auto second = aobench::parse_config(other, error);
  ASSERT_TRUE(second.has_value()) << error;
  EXPECT_EQ(second->settings.ao_settings.estimator, ssao::Estimator::sphere);
  EXPECT_EQ(second->settings.ao_settings.samples, 7);
  EXPECT_FALSE(second->settings.ao_settings.half_resolution);
  EXPECT_EQ(aobench::describe(second->settings), other);
}

TEST(AobenchConfigs, SavingsCanBeSwitchedOffOneByOne) {
  std::string error;
  const std::string core =
      "estimator=hemisphere,samples=16,radii=2,pattern=jittered,blur=off,resolution=full,depth-chain=off,skip-radii=on";
  const auto config = aobench::parse_config(core + ",skip-background=off,untextured-variant=off,reuse-ao=on,prepass=off", error);
  ASSERT_TRUE(config.has_value()) << error;
  EXPECT_FALSE(config->settings.ao_settings.skip_background);
  EXPECT_FALSE(config->settings.untextured_variant);
  EXPECT_TRUE(config->settings.reuse_static_ao);
  EXPECT_EQ(config->settings.prepass, render::Prepass::off);
  // The savings follow the core keys, in the codec's table order, because they differ from the default.
  const std::string expected = core + ",skip-background=off,untextured-variant=off,reuse-ao=on,prepass=off";
  EXPECT_EQ(aobench::describe(config->settings), expected);
  const auto again = aobench::parse_config(expected, error);
  ASSERT_TRUE(again.has_value()) << error;
  EXPECT_FALSE(again->settings.ao_settings.skip_background);
  EXPECT_FALSE(again->settings.untextured_variant);
  EXPECT_TRUE(again->settings.reuse_static_ao);
  EXPECT_EQ(again->settings.prepass, render::Prepass::off);
  // Given in another order, the name still comes out in the one order.
  const auto shuffled =
      aobench::parse_config("prepass=off,reuse-ao=on,untextured-variant=off,skip-background=off," + core, error);
  ASSERT_TRUE(shuffled.has_value()) << error;
  EXPECT_EQ(aobench::describe(shuffled->settings), expected);
  // Settings left at the player's default stay out of the name.
  EXPECT_EQ(aobench::describe(aobench::parse_config("default", error)->settings).find("background"), std::string::npos);
  EXPECT_FALSE(aobench::parse_config("skip-background=maybe", error).has_value());
  EXPECT_NE(error.find("skip-background: expected on|off, got 'maybe'"), std::string::npos) << error;
  EXPECT_FALSE(aobench::parse_config("prepass=sometimes", error).has_value());
}

// The fields an ablation may change, by the codec's key, read from the settings directly.
std::string field(const render::FrameSettings& s, const std::string& key) {
  const ssao::AoSettings& ao = s.ao_settings;
  auto on_off = [](bool on) { return std::string(on ? "on" : "off"); };
  if (key == "skip-background") return on_off(ao.skip_background);
  if (key == "untextured-variant") return on_off(s.untextured_variant);
  if (key == "reuse-ao") return on_off(s.reuse_static_ao);
  if (key == "prepass") return s.prepass == render::Prepass::on ? "on" : s.prepass == render::Prepass::off ? "off" : "auto";
  if (key == "depth-chain") return on_off(ao.depth_chain);
  if (key == "resolution") return ao.half_resolution ? "half" : "full";
  if (key == "skip-radii") return on_off(ao.skip_radii);
  if (key == "radii") return std::to_string(ao.radii);
  if (key == "samples") return std::to_string(ao.samples);
  if (key == "estimator") return std::string(ssao::name(ao.estimator));
  if (key == "pattern") return std::string(ssao::name(ao.pattern));
  if (key == "blur") return std::string(ssao::name(s.blur.mode));
  if (key == "ao") return on_off(s.ao);
  return "?";
}

TEST(AobenchConfigs, AblationTurnsOffOneSavingAtATime) {
  const auto configs = aobench::sweep("ablation");
  // Each entry: its name, and every field it must change from the default with the value it must
  // have. Every other field must equal the default's, and each listed one must differ from it: an
  // ablation that changes nothing (its saving already off by default, or its key ignored) fails.
  using Changes = std::vector<std::pair<std::string, std::string>>;
  const std::vector<std::pair<std::string, Changes>> expected = {
      {"default", {}},
      {"skip-background=off", {{"skip-background", "off"}}},
      {"untextured-variant=off", {{"untextured-variant", "off"}}},
      {"reuse-ao=on", {{"reuse-ao", "on"}}},
      {"prepass=on", {{"prepass", "on"}}},
      {"prepass=off", {{"prepass", "off"}}},
      {"depth-chain=on", {{"depth-chain", "on"}}},
      {"resolution=full", {{"resolution", "full"}}},
      {"radii=5", {{"radii", "5"}}},
      {"radii=5,skip-radii=off", {{"radii", "5"}, {"skip-radii", "off"}}},
      {"radii=5,depth-chain=on", {{"radii", "5"}, {"depth-chain", "on"}}},
  };
  ASSERT_EQ(configs.size(), expected.size());
  // The baseline: the player's defaults with every frame computing its AO (aobench times every frame).
  render::FrameSettings baseline;
  baseline.reuse_static_ao = false;
  const char* fields[] = {
      "skip-background", "untextured-variant", "reuse-ao", "prepass", "depth-chain", "resolution", "skip-radii", "radii",
      "samples",         "estimator",          "pattern",  "blur",    "ao"};
  for (size_t i = 0; i < configs.size(); ++i) {
    const auto& [name, changes] = expected[i];
    EXPECT_EQ(configs[i].name, name) << "entry " << i;
    for (const char* key : fields) {
      const auto change = std::find_if(changes.begin(), changes.end(), [&](const auto& c) { return c.first == key; });
      const std::string value = field(configs[i].settings, key), base = field(baseline, key);
      if (change == changes.end()) {
        EXPECT_EQ(value, base) << name << ": " << key << " changed";
      } else {
        EXPECT_EQ(value, change->second) << name << ": " << key;
        EXPECT_NE(base, change->second) << name << ": " << key << " is " << base << " by default, so this changes nothing";
      }
    }
  }
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
  EXPECT_EQ(settings.output, render::Picture::ao);
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

// Every key at the edges of what it accepts: the values just inside are taken (and read back as
// written), those just outside are refused with the message the player prints, and leave the
// settings as they were. Written out here rather than derived from the codec's own table, so a
// range that drifts from its documented choices fails.
TEST(SettingsCodec, EveryKeyAcceptsItsRangeAndRefusesJustOutsideIt) {
  struct Case {
    const char* key;
    std::vector<const char*> accepted, refused;
    const char* expected;  // what the error says is expected
  };
  const std::vector<Case> cases = {
      {"ao", {"on", "off"}, {"yes", "1", ""}, "on|off"},
      {"estimator", {"sphere", "hemisphere", "horizon"}, {"ray", "Sphere"}, "sphere|hemisphere|horizon"},
      {"precision", {"highp", "mediump"}, {"lowp", "fp16"}, "highp|mediump"},
      {"samples", {"1", "64", "32"}, {"0", "65", "-1", "1.5", "8x", ""}, "1..64"},
      {"steps", {"1", "32", "8"}, {"0", "33", "-1", "4.5", ""}, "1..32"},
      {"radii", {"1", "5"}, {"0", "6", "2.0"}, "1..5"},
      {"radius", {"0", "2.5", "1e-3"}, {"-0.001", "-1", "inf", "nan", "1e", "x"}, "a number >= 0"},
      {"pattern", {"random", "jittered", "latin", "poisson"}, {"halton"}, "random|jittered|latin|poisson"},
      {"blur", {"gaussian", "bilateral", "denoise", "off"}, {"box", "on"}, "gaussian|bilateral|denoise|off"},
      {"resolution", {"full", "half"}, {"quarter", "on"}, "full|half"},
      {"depth-chain", {"on", "off"}, {"true"}, "on|off"},
      {"skip-radii", {"on", "off"}, {"no"}, "on|off"},
      {"skip-background", {"on", "off"}, {"0"}, "on|off"},
      {"untextured-variant", {"on", "off"}, {"auto"}, "on|off"},
      {"reuse-ao", {"on", "off"}, {"auto"}, "on|off"},
      {"temporal", {"on", "off"}, {"1"}, "on|off"},
      {"motion-vectors", {"on", "off"}, {"yes"}, "on|off"},
      {"present-tiles", {"on", "off"}, {"tiles"}, "on|off"},
      {"ao-strength", {"0", "1", "1.5", "8"}, {"-0.5", "8.5", "inf", "nan", "x", ""}, "0..8"},
      {"history", {"1", "255", "32"}, {"0", "256", "-1", "8.0", ""}, "1..255"},
      {"prepass", {"on", "off", "auto"}, {"maybe"}, "on|off|auto"},
      {"view", {"color", "ao", "normal", "depth"}, {"colour"}, "color|ao|normal|depth"},
  };
  // Every key of the codec is covered.
  std::vector<std::string> covered;
  for (const Case& c : cases) covered.emplace_back(c.key);
  for (const render::SettingKey& key : render::setting_keys())
    EXPECT_NE(std::find(covered.begin(), covered.end(), key.key), covered.end()) << key.key << " has no case";
  for (const Case& c : cases) {
    for (const char* value : c.accepted) {
      render::FrameSettings settings;
      std::string error;
      EXPECT_TRUE(render::apply_setting(settings, c.key, value, error)) << c.key << "=" << value << ": " << error;
      if (std::string_view(c.key) != "radius") {  // floats read back in their shortest form
        EXPECT_EQ(render::setting_value(settings, c.key), value) << c.key;
      }
      EXPECT_TRUE(render::validate_setting(c.key, value, error)) << c.key << "=" << value;
    }
    for (const char* value : c.refused) {
      render::FrameSettings settings;
      const render::FrameSettings before;
      std::string error;
      EXPECT_FALSE(render::apply_setting(settings, c.key, value, error)) << c.key << "=" << value;
      EXPECT_EQ(error, std::string(c.key) + ": expected " + c.expected + ", got '" + value + "'");
      EXPECT_EQ(render::describe(settings, before), "") << c.key << "=" << value << " changed the settings";
      EXPECT_FALSE(render::validate_setting(c.key, value, error)) << c.key << "=" << value;
    }
  }
}

TEST(AobenchConfigs, SweepsCoverTheGrid) {
  // quick: 3 estimators x 4 sample counts x 3 radii x 3 blurs x 2 scales, plus 4 patterns at the paper's point.
  EXPECT_EQ(aobench::sweep("quick").size(), 3u * 4 * 3 * 3 * 2 + 4);
  EXPECT_EQ(aobench::sweep("full").size(), (2u * 4 + 1) * 6 * 5 * 3 * 2);  // the horizon with one pattern
}

TEST(AobenchChart, ParetoFrontKeepsOnlyUnbeatenPoints) {
  std::vector<aobench::ChartPoint> points = {{10, 0.5, false, ""}, {20, 0.2, false, ""}, {15, 0.6, false, ""},
                                             {30, 0.2, false, ""}, {40, 0.1, false, ""}, {10, 0.5, false, ""}};
  // (15, 0.6) is beaten by (10, 0.5); (30, 0.2) by (20, 0.2); the second (10, 0.5) ties the first.
  EXPECT_EQ(aobench::pareto_front(points), (std::vector<size_t>{0, 1, 4}));
}

using Rgb = std::array<int, 3>;

Rgb rgb8(const float (&colour)[3]) {
  return {static_cast<int>(std::lround(colour[0] * 255.0f)), static_cast<int>(std::lround(colour[1] * 255.0f)),
          static_cast<int>(std::lround(colour[2] * 255.0f))};
}

struct Chart {
  OIIO::ImageBuf image;
  Rgb at(int x, int y) const {
    float p[3] = {0, 0, 0};
    image.getpixel(x, y, p, 3);
    return rgb8(p);
  }
  // Pixels of `colour` in the box from (x0, y0) to (x1, y1), inclusive; within 2 of 255 per
  // channel, for the 8-bit rounding.
  int count(const float (&colour)[3], int x0, int y0, int x1, int y1) const {
    const Rgb want = rgb8(colour);
    int n = 0;
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Rgb got = at(x, y);
        n += std::abs(got[0] - want[0]) <= 2 && std::abs(got[1] - want[1]) <= 2 && std::abs(got[2] - want[2]) <= 2;
      }
    return n;
  }
};

// Where the chart's layout (chart.h) puts time `t` and error `e`, worked out here from the layout's
// description rather than by the chart's own code: an axis swapped or reversed moves every point.
struct Axes {
  double log_min, log_max, e_top;
  int x(double t) const {
    const auto& l = aobench::kChartLayout;
    return l.left + static_cast<int>((std::log10(t) - log_min) / (log_max - log_min) * (l.width - l.left - l.right));
  }
  int y(double e) const {
    const auto& l = aobench::kChartLayout;
    return l.height - l.bottom - static_cast<int>(e / e_top * (l.height - l.top - l.bottom));
  }
};

TEST(AobenchChart, PointsFrontAndMarksAreDrawnWhereTheDataSays) {
  // Front: (10, 0.5), (20, 0.2), (40, 0.1). Beaten: (15, 0.6) and (30, 0.2), which is marked.
  const std::vector<aobench::ChartPoint> points = {
      {10, 0.5, false, ""}, {20, 0.2, false, ""}, {15, 0.6, false, ""}, {30, 0.2, false, "paper"}, {40, 0.1, false, ""}};
  const std::string path = (std::filesystem::temp_directory_path() / "aobench_chart_test.png").string();
  std::string error;
  ASSERT_TRUE(aobench::write_chart(path, points, "test", "MAE", error)) << error;
  Chart chart{OIIO::ImageBuf(path)};
  ASSERT_TRUE(chart.image.read(0, 0, true, OIIO::TypeDesc::UINT8)) << chart.image.geterror();
  std::filesystem::remove(path);
  const auto& l = aobench::kChartLayout;
  ASSERT_EQ(chart.image.spec().width, l.width);
  ASSERT_EQ(chart.image.spec().height, l.height);
  ASSERT_EQ(chart.image.spec().nchannels, 3);

  const Axes axes{std::log10(10.0) - aobench::kTimePadDecades, std::log10(40.0) + aobench::kTimePadDecades,
                  0.6 * aobench::kErrorHeadroom};
  // Front points: a filled 9x9 square each.
  for (int i : {0, 1, 4}) {
    const int x = axes.x(points[i].time_ms), y = axes.y(points[i].error);
    EXPECT_EQ(chart.count(aobench::kFrontColour, x - 4, y - 4, x + 4, y + 4), 81)
        << "front point " << i << " at (" << x << ", " << y << ")";
  }
  // Beaten points: a 5x5 dot, and nothing of the front's colour around it.
  for (int i : {2, 3}) {
    const int x = axes.x(points[i].time_ms), y = axes.y(points[i].error);
    EXPECT_EQ(chart.count(aobench::kPointColour, x - 2, y - 2, x + 2, y + 2), 25)
        << "point " << i << " at (" << x << ", " << y << ")";
    EXPECT_EQ(chart.count(aobench::kFrontColour, x - 6, y - 6, x + 6, y + 6), 0) << "point " << i << " drawn as on the front";
  }
  // The front line: halfway between consecutive front points.
  for (auto [a, b] : {std::pair{0, 1}, std::pair{1, 4}}) {
    const int x = (axes.x(points[a].time_ms) + axes.x(points[b].time_ms)) / 2;
    const int y = (axes.y(points[a].error) + axes.y(points[b].error)) / 2;
    EXPECT_GT(chart.count(aobench::kFrontColour, x - 1, y - 1, x + 1, y + 1), 0)
        << "front line " << a << "-" << b << " near (" << x << ", " << y << ")";
  }
  // The marked point: a square outline two pixels thick, 8 out, and its label to the right.
  const int mx = axes.x(30), my = axes.y(0.2);
  EXPECT_EQ(chart.count(aobench::kMarkColour, mx - 8, my - 8, mx + 8, my - 7), 2 * 17) << "mark's top edge";
  EXPECT_EQ(chart.count(aobench::kMarkColour, mx - 8, my + 7, mx + 8, my + 8), 2 * 17) << "mark's bottom edge";
  EXPECT_GT(chart.count(aobench::kMarkColour, mx + 12, my - 30, mx + 80, my), 20) << "mark's label";
  EXPECT_EQ(chart.count(aobench::kMarkColour, axes.x(10) - 8, axes.y(0.5) - 8, axes.x(10) + 8, axes.y(0.5) + 8), 0)
      << "an unmarked point drawn as marked";
  // No series colour outside the plot area; the axes dark along its left and bottom edges.
  EXPECT_EQ(chart.count(aobench::kFrontColour, 0, 0, l.width - 1, l.top - 1), 0);
  EXPECT_EQ(chart.count(aobench::kPointColour, 0, l.height - l.bottom + 1, l.width - 1, l.height - 1), 0);
  const Rgb time_axis = chart.at(l.left + 500, l.height - l.bottom), error_axis = chart.at(l.left, l.top + 300);
  EXPECT_EQ(time_axis, error_axis);
  EXPECT_LT(time_axis[0], 100) << "no dark time axis along the bottom of the plot";
  EXPECT_EQ(chart.at(l.width - 5, 5), (Rgb{255, 255, 255}));  // background
}

TEST(AobenchChart, NoPointsIsAnErrorNamingTheFile) {
  const std::string path = (std::filesystem::temp_directory_path() / "aobench_empty_chart.png").string();
  std::filesystem::remove(path);
  std::string error;
  EXPECT_FALSE(aobench::write_chart(path, {}, "test", "MAE", error));
  EXPECT_EQ(error, path + ": no points to chart");
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
