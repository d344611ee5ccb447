#include "configs.h"

#include <sstream>

namespace aobench {
namespace {

render::FrameSettings defaults() {
  render::FrameSettings settings;  // the player's defaults
  settings.reuse_static_ao = false;  // every frame computes its AO, so every frame times it
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

bool on_off(const std::string& value, bool& out) {
  if (value == "on") out = true;
  else if (value == "off") out = false;
  else return false;
  return true;
}

}  // namespace

std::string describe(const render::FrameSettings& s) {
  std::ostringstream out;
  out << "estimator=" << ssao::name(s.ao_settings.estimator) << ",samples=" << s.ao_settings.samples
      << ",radii=" << s.ao_settings.radii << ",pattern=" << ssao::name(s.ao_settings.pattern)
      << ",blur=" << ssao::name(s.blur.mode) << ",scale=" << (s.ao_settings.half_resolution ? "half" : "full")
      << ",chain=" << (s.ao_settings.depth_chain ? "on" : "off") << ",skip=" << (s.ao_settings.skip_radii ? "on" : "off");
  const render::FrameSettings usual = defaults();
  if (s.ao_settings.skip_background != usual.ao_settings.skip_background)
    out << ",background=" << (s.ao_settings.skip_background ? "skip" : "shade");
  if (s.untextured_variant != usual.untextured_variant) out << ",untextured=" << (s.untextured_variant ? "variant" : "fetch");
  if (s.reuse_static_ao != usual.reuse_static_ao) out << ",reuse=" << (s.reuse_static_ao ? "on" : "off");
  if (s.prepass != usual.prepass) out << ",prepass=" << (s.prepass == render::Prepass::automatic ? "auto" : render::name(s.prepass));
  return out.str();
}

std::optional<Config> parse_config(const std::string& text, std::string& error) {
  if (text == "paper") return Config{"paper", paper()};
  if (text == "default") return Config{"default", defaults()};
  Config config{text, defaults()};
  std::istringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    const size_t equals = item.find('=');
    if (equals == std::string::npos) {
      error = "--config '" + text + "': '" + item + "' is not key=value (or use the names paper, default)";
      return std::nullopt;
    }
    const std::string key = item.substr(0, equals), value = item.substr(equals + 1);
    auto& ao = config.settings.ao_settings;
    bool ok = true;
    try {
      if (key == "estimator") {
        const auto parsed = ssao::parse_estimator(value);
        ok = parsed.has_value();
        if (ok) ao.estimator = *parsed;
      } else if (key == "pattern") {
        const auto parsed = ssao::parse_pattern(value);
        ok = parsed.has_value();
        if (ok) ao.pattern = *parsed;
      } else if (key == "blur") {
        const auto parsed = ssao::parse_blur(value);
        ok = parsed.has_value();
        if (ok) config.settings.blur.mode = *parsed;
      } else if (key == "samples") {
        ao.samples = std::stoi(value);
        ok = ao.samples >= 1 && ao.samples <= SSAO_MAX_SAMPLES;
      } else if (key == "radii") {
        ao.radii = std::stoi(value);
        ok = ao.radii >= 1 && ao.radii <= SSAO_MAX_RADII;
      } else if (key == "scale") {
        ok = value == "full" || value == "half";
        ao.half_resolution = value == "half";
      } else if (key == "chain") {
        ok = on_off(value, ao.depth_chain);
      } else if (key == "skip") {
        ok = on_off(value, ao.skip_radii);
      } else if (key == "background") {
        ok = value == "skip" || value == "shade";
        ao.skip_background = value == "skip";
      } else if (key == "untextured") {
        ok = value == "variant" || value == "fetch";
        config.settings.untextured_variant = value == "variant";
      } else if (key == "reuse") {
        ok = on_off(value, config.settings.reuse_static_ao);
      } else if (key == "prepass") {
        ok = value == "on" || value == "off" || value == "auto";
        config.settings.prepass = value == "on" ? render::Prepass::on : value == "off" ? render::Prepass::off : render::Prepass::automatic;
      } else {
        error = "--config '" + text + "': unknown key '" + key +
                "' (expected estimator, samples, radii, pattern, blur, scale, chain, skip, background, untextured, reuse, prepass)";
        return std::nullopt;
      }
    } catch (const std::exception&) {
      ok = false;
    }
    if (!ok) {
      error = "--config '" + text + "': '" + value + "' is not a valid " + key;
      return std::nullopt;
    }
  }
  return config;
}

std::vector<Config> sweep(const std::string& kind) {
  std::vector<Config> configs;
  if (kind == "ablation") {
    std::string error;
    for (const char* spec : {"default", "background=shade", "untextured=fetch", "reuse=on", "prepass=on", "prepass=off",
                             "chain=on", "scale=half", "radii=5", "radii=5,skip=off", "radii=5,chain=on"})
      configs.push_back(*parse_config(spec, error));
    return configs;
  }
  const bool full = kind == "full";
  const std::vector<int> samples = full ? std::vector<int>{2, 4, 8, 16, 32, 64} : std::vector<int>{4, 8, 16, 32};
  const std::vector<int> radii = full ? std::vector<int>{1, 2, 3, 4, 5} : std::vector<int>{1, 3, 5};
  const std::vector<ssao::Pattern> patterns = full ? std::vector<ssao::Pattern>(std::begin(ssao::kPatterns), std::end(ssao::kPatterns))
                                                   : std::vector<ssao::Pattern>{ssao::Pattern::poisson};
  for (ssao::Estimator estimator : ssao::kEstimators)
    for (int n : samples)
      for (int k : radii)
        for (ssao::Pattern pattern : patterns)
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
