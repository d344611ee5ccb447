#pragma once
// AO configurations for the benchmark: named ones, "key=value,..." specifications, and sweep grids.
#include "render/settings.h"

#include <optional>
#include <string>
#include <vector>

namespace aobench {

struct Config {
  std::string name;  // "paper", "default" or the specification itself
  render::FrameSettings settings;
};

// `paper`: the paper's configuration (sphere estimator, 8 samples x 5 radii, Gaussian blur, full
// resolution, none of the player's skips). `default`: what `player render` uses. Otherwise a
// comma-separated list of key=value in the settings codec's names (render/settings.h: the long
// options of `player render`, e.g. estimator=hemisphere,samples=16,resolution=full,reuse-ao=on),
// applied to the default. Returns nullopt and says why.
std::optional<Config> parse_config(const std::string& text, std::string& error);

// The specification that parse_config() reads back to the same settings: the AO keys always, the
// others only where they differ from the default.
std::string describe(const render::FrameSettings& settings);

// quick: every estimator x samples {4, 8, 16, 32} x radii {1, 3, 5} x blur x scale, Poisson pattern,
// plus every pattern at the paper's point. full: estimator x samples {2..64} x radii {1..5} x
// pattern x blur x scale.
// ablation: the default, then each of the player's savings turned off (or the depth chain and half
// resolution turned on) one at a time, and radius skipping and the chain at 5 radii where they act.
std::vector<Config> sweep(const std::string& kind);

}  // namespace aobench
