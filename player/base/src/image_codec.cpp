#include "base/image_codec.h"

#include <dlfcn.h>
#include <unistd.h>

#include <filesystem>
#include <mutex>

namespace base::images {
namespace {

namespace fs = std::filesystem;

constexpr const char* kModule = "libssao-player-images.so";

struct Loaded {
  const Codec* codec = nullptr;
  std::string path, error;
};

// Where the module is: beside the installed player (/usr/bin/player and
// /usr/lib/ssao-player/), which the build tree repeats for its player (build/player/player and
// build/lib/ssao-player/); every other program of the build tree (tests, tools) finds the module
// of its own build by the path the build gave it.
std::vector<std::string> candidates() {
  std::vector<std::string> paths;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) paths.push_back((exe.parent_path().parent_path() / "lib" / "ssao-player" / kModule).string());
#ifdef PLAYER_IMAGE_MODULE_BUILD_PATH
  paths.push_back(PLAYER_IMAGE_MODULE_BUILD_PATH);
#endif
  return paths;
}

const Loaded& loaded() {
  static Loaded result;
  static std::once_flag once;
  std::call_once(once, [] {
    std::string tried;
    for (const std::string& path : candidates()) {
      if (access(path.c_str(), F_OK) != 0) {
        tried += (tried.empty() ? "" : ", ") + path;
        continue;
      }
      // Never closed: OpenImageIO keeps process-wide state (plugins, threads) to the end.
      void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        const char* why = dlerror();
        result.error = "image support: cannot load " + path + ": " + (why ? why : "unknown reason");
        return;
      }
      auto* entry = reinterpret_cast<const Codec* (*)()>(dlsym(handle, "player_image_codec_v1"));
      result.codec = entry ? entry() : nullptr;
      if (!result.codec) {
        result.error = "image support: " + path + " is not this player's image module (no player_image_codec_v1)";
        return;
      }
      result.path = path;
      return;
    }
    result.error = std::string("image support: ") + kModule + " is not installed (looked for " + tried + ")";
  });
  return result;
}

}  // namespace

std::unique_ptr<Reader> make_reader(const std::string& format, std::string& error) {
  const Loaded& module = loaded();
  if (!module.codec) {
    error = module.error;
    return nullptr;
  }
  return module.codec->make_reader(format, error);
}

WriteFailure write(const std::string& path, const WriteSpec& spec, const void* pixels, std::string& error) {
  const Loaded& module = loaded();
  if (!module.codec) {
    error = module.error;
    return WriteFailure::no_writer;
  }
  return module.codec->write(path, spec, pixels, error);
}

std::string describe() {
  const Loaded& module = loaded();
  return module.codec ? module.path + " (" + module.codec->library + ")" : module.error;
}

bool preload(std::string& error) {
  const Loaded& module = loaded();
  if (!module.codec) error = module.error;
  return module.codec != nullptr;
}

}  // namespace base::images
