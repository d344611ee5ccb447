#include "shader_cache.h"

#include "scene/environment.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace app {
namespace {

namespace fs = std::filesystem;

std::string environment(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

}  // namespace

std::string shader_cache_dir(const std::string& option) {
  if (option == "off") return {};
  if (!option.empty()) return option;
  // systemd gives one absolute path per CacheDirectory= entry, separated by colons.
  if (const std::string cache = environment("CACHE_DIRECTORY"); !cache.empty())
    return (fs::path(cache.substr(0, cache.find(':'))) / "shaders").string();
  if (const std::string xdg = environment("XDG_CACHE_HOME"); !xdg.empty() && xdg.front() == '/')
    return (fs::path(xdg) / "ssao-player" / "shaders").string();
  if (const std::string home = environment("HOME"); !home.empty())
    return (fs::path(home) / ".cache" / "ssao-player" / "shaders").string();
  return {};
}

std::string prepare_driver_cache(const std::string& dir) {
  if (!environment("MESA_SHADER_CACHE_DIR").empty() || !environment("MESA_SHADER_CACHE_DISABLE").empty()) return {};
  if (dir.empty()) {
    setenv("MESA_SHADER_CACHE_DISABLE", "true", 0);
    return {};
  }
  const fs::path mesa = fs::path(dir) / "mesa";
  std::error_code ec;
  fs::create_directories(mesa, ec);
  if (ec) return "cannot make " + mesa.string() + ": " + ec.message();
  setenv("MESA_SHADER_CACHE_DIR", mesa.c_str(), 0);
  return {};
}

std::string open_program_store(gl::Session& session, const std::string& dir) {
  scene::keep_prepared_environments(dir.empty() ? fs::path() : fs::path(dir) / "environments");
  if (dir.empty()) return "shader cache: off";
  std::string reason;
  std::unique_ptr<gl::ProgramStore> store = gl::ProgramStore::open((fs::path(dir) / "programs").string(), session.caps(), reason);
  if (!store) return "shader cache: " + dir + ", without program binaries (" + reason + ")";
  session.programs().use_store(std::move(store));
  return "shader cache: " + dir;
}

std::string program_counts(const gl::ProgramCache& programs) {
  std::string text = std::to_string(programs.compiled()) + " compiled";
  if (const gl::ProgramStore* store = programs.store()) {
    text += ", " + std::to_string(store->loaded()) + " loaded from " + store->dir();
    if (store->rejected() > 0) text += ", " + std::to_string(store->rejected()) + " damaged or stale file(s) compiled anew";
  }
  if (!programs.store_problem().empty()) text += "; not kept: " + programs.store_problem();
  return text;
}

std::string environment_counts() {
  const scene::EnvironmentCacheCounts counts = scene::environment_cache_counts();
  std::string text = std::to_string(counts.prepared) + " prepared";
  if (!counts.dir.empty()) {
    text += ", " + std::to_string(counts.loaded) + " loaded from " + counts.dir.string();
    if (counts.rejected > 0) text += ", " + std::to_string(counts.rejected) + " damaged file(s) prepared anew";
  }
  if (!counts.problem.empty()) text += "; not kept: " + counts.problem;
  return text;
}

}  // namespace app
