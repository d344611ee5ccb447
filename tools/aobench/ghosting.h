#pragma once
// aobench --ghosting: how much an animated scene's temporal AO lags behind its moving parts.
#include <string>
#include <vector>

namespace aobench {

struct GhostingOptions {
  std::vector<std::string> scenes;  // animated scenes; none: the animated samples in ../shared/samples
  int width = 1024, height = 768;
  std::string platform = "auto";
  int frames = 32;  // accumulated frames played up to each measured pose, at `fps`
  double fps = 30.0;
  int poses = 3;        // measured poses, spread over the animation's loop
  int converged = 128;  // frames averaged at the frozen pose for the reference
  double goal = 1.2;    // accumulated error over one frame's, at most, over moving pixels
};

// Prints a table per scene and pose and the mean; returns the process exit code (0 also when a ratio
// is over the goal: that is a figure, printed as such; 1 on errors).
int run_ghosting(GhostingOptions options);

}  // namespace aobench
