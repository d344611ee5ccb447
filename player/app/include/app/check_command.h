#pragma once
#include <ostream>
#include <string>
#include <vector>

namespace app {

// Loads each scene exactly as `play` and `render` do, with no GL context: what an installer runs on
// content before copying it onto a kiosk. Per scene one line, "ok: SCENE: N triangles, M instances,
// K textures" or "error: SCENE: why", after its "warning: SCENE: ..." lines (a texture drawn white).
// Exit status 0 when every scene loads, 1 when any is refused.
int run_check(const std::vector<std::string>& scenes, std::ostream& out, std::ostream& err);

}  // namespace app
