#include "configs.h"

#include "render/settings.h"

namespace aobench {
namespace {

render::FrameSettings defaults() {
  render::FrameSettings settings;    // the player's defaults
  settings.reuse_static_ao = false;  // every frame computes its AO, so every frame times it
  // One frame's AO: the timed frames repeat one camera, and with accumulation the estimate would be
  // their average. temporal=on in --configs measures that.
  settings.temporal = false;
  return settings;
}

render::FrameSettings paper() {
  render::FrameSettings settings = defaults();
  settings.ao_settings.estimator = ssao::Estimator::sphere;
  settings.ao_settings.samples = 8;
  settings.ao_settings.radii = 5;
  settings.ao_settings.pattern = ssao::Pattern::jittered;
  settings.ao_settings.half_resolution = false;
  settings.ao_settings.depth_chain = false;
  settings.ao_settings.skip_radii = false;
  settings.blur.mode = ssao::Blur::gaussian;
  return settings;
}

// Always written by describe(), so a configuration reads the same in every row of the CSV.
constexpr const char* kCoreKeys[] = {"estimator", "samples",    "radii",       "pattern",
                                     "blur",      "resolution", "depth-chain", "skip-radii"};

}  // namespace

std::string describe(const render::FrameSettings& s) {
  std::string text;
  for (const char* key : kCoreKeys) text += (text.empty() ? "" : ",") + std::string(key) + "=" + render::setting_value(s, key);
  // The other keys only where they differ from the default.
  render::FrameSettings rest = defaults();
  for (const char* key : kCoreKeys) {
    std::string ignored;
    render::apply_setting(rest, key, render::setting_value(s, key), ignored);
  }
  const std::string differences = render::describe(s, rest);
  return differences.empty() ? text : text + "," + differences;
}

std::optional<Config> parse_config(const std::string& text, std::string& error) {
  if (text == "paper") return Config{"paper", paper()};
  if (text == "default") return Config{"default", defaults()};
  Config config{text, defaults()};
  if (!render::apply_settings(config.settings, text, error)) {
    error = "--config '" + text + "': " + error + " (or use the names paper, default)";
    return std::nullopt;
  }
  return config;
}

std::vector<Config> sweep(const std::string& kind) {
  std::vector<Config> configs;
  if (kind == "ablation") {
    std::string error;
    for (const char* spec :
         {"default", "skip-background=off", "untextured-variant=off", "reuse-ao=on", "prepass=on", "prepass=off",
          "depth-chain=on", "resolution=full", "radii=5", "radii=5,skip-radii=off", "radii=5,depth-chain=on"})
      configs.push_back(*parse_config(spec, error));
    return configs;
  }
  const bool full = kind == "full";
  const std::vector<int> samples = full ? std::vector<int>{2, 4, 8, 16, 32, 64} : std::vector<int>{4, 8, 16, 32};
  const std::vector<int> radii = full ? std::vector<int>{1, 2, 3, 4, 5} : std::vector<int>{1, 3, 5};
  const std::vector<ssao::Pattern> patterns =
      full ? std::vector<ssao::Pattern>(std::begin(ssao::kPatterns), std::end(ssao::kPatterns))
           : std::vector<ssao::Pattern>{ssao::Pattern::poisson};
  // The horizon spaces its slices evenly whatever the pattern: one pattern measures it.
  const std::vector<ssao::Pattern> horizon_patterns{ssao::Pattern::poisson};
  for (ssao::Estimator estimator : ssao::kEstimators)
    for (int n : samples)
      for (int k : radii)
        for (ssao::Pattern pattern : estimator == ssao::Estimator::horizon ? horizon_patterns : patterns)
          for (ssao::Blur blur : {ssao::Blur::off, ssao::Blur::gaussian, ssao::Blur::bilateral})
            for (bool half : {false, true}) {
              render::FrameSettings settings = defaults();
              settings.ao_settings.estimator = estimator;
              settings.ao_settings.samples = n;
              settings.ao_settings.radii = k;
              settings.ao_settings.pattern = pattern;
              settings.blur.mode = blur;
              settings.ao_settings.half_resolution = half;
              configs.push_back({describe(settings), settings});
            }
  if (!full)
    for (ssao::Pattern pattern : ssao::kPatterns) {
      render::FrameSettings settings = paper();
      settings.ao_settings.pattern = pattern;
      configs.push_back({describe(settings), settings});
    }
  return configs;
}

}  // namespace aobench
