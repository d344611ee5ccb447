#include "app/check_command.h"

#include "scene/load.h"

namespace app {
namespace {

std::string counted(size_t n, const char* what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

}  // namespace

int run_check(const std::vector<std::string>& scenes, std::ostream& out, std::ostream& err) {
  int refused = 0;
  for (const std::string& spec : scenes) {
    scene::Scene scene;
    std::string error;
    if (!scene::load(spec, scene, error, out)) {
      err << "error: " << error << "\n";
      ++refused;
      continue;
    }
    out << "ok: " << spec << ": " << counted(scene.triangle_count(), "triangle") << ", "
        << counted(scene.instances.size(), "instance") << ", " << counted(scene.textures.size(), "texture") << "\n";
  }
  if (scenes.size() > 1)
    out << "check: " << scenes.size() - static_cast<size_t>(refused) << " of " << scenes.size() << " scenes load\n";
  return refused == 0 ? 0 : 1;
}

}  // namespace app
