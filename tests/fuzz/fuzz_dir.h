#pragma once
// A scratch folder per fuzzing process, removed at exit: targets whose parser takes a path (or
// resolves relative paths against one) write there, so parallel jobs never share a file.
#include <unistd.h>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace fuzz {

inline const std::filesystem::path& scratch_dir() {
  // Never destroyed: the removal runs from atexit, after the destructor of a static path (registered
  // once its initialiser returns, so run first) would already have emptied it, and nothing was
  // removed.
  static const std::filesystem::path* const dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/player-fuzz-XXXXXX";
    if (!::mkdtemp(pattern.data())) std::abort();  // no scratch folder: nothing here can run
    const auto* made = new std::filesystem::path(pattern);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(scratch_dir(), ec);
    });
    return made;
  }();
  return *dir;
}

}  // namespace fuzz
