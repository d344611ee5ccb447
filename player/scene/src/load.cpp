#include "scene/load.h"

#include "scene/animation.h"

#include "scene/environment.h"
#include "scene/gltf_loader.h"
#include "scene/procedural.h"

#include <ostream>

namespace scene {
namespace {
constexpr std::string_view kBuiltinPrefix = "builtin:";
}  // namespace

bool load_environment_spec(const std::string& spec, std::shared_ptr<const Environment>& out, std::string& error) {
  out.reset();
  // Null: the renderer's built-in studio (studio_environment(), prepared once per process).
  if (spec.empty() || spec == "builtin:studio") return true;
  if (spec.rfind(kBuiltinPrefix, 0) == 0) {
    error = spec + ": no such built-in environment (expected builtin:studio)";
    return false;
  }
  auto environment = std::make_shared<Environment>();
  if (!load_environment(spec, *environment, error)) return false;
  out = std::move(environment);
  return true;
}

bool load(const std::string& spec, Scene& out, std::string& error, std::ostream& log, const LoadOptions& options) {
  if (spec.rfind(kBuiltinPrefix, 0) == 0) {
    const std::string name = spec.substr(kBuiltinPrefix.size());
    if (auto built = make_builtin(name)) {
      out = std::move(*built);
      recenter_meshes(out);
      return true;
    }
    error = spec + ": no such built-in scene (expected one of:";
    for (const std::string& known : builtin_names()) error += " builtin:" + known;
    error += ")";
    return false;
  }
  LoadReport report;
  if (!load_gltf(spec, out, report, options)) {
    error = report.error;
    return false;
  }
  recenter_meshes(out);
  include_animation_in_bounds(out);
  for (const std::string& warning : report.warnings) log << "warning: " << spec << ": " << warning << "\n";
  return true;
}

}  // namespace scene
