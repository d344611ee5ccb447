#pragma once
// A scratch folder per fuzzing process, removed at exit: targets whose parser takes a path (or
// resolves relative paths against one) write there, so parallel jobs never share a file.
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace fuzz {

inline const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/player-fuzz-XXXXXX";
    if (!::mkdtemp(pattern.data())) std::abort();  // no scratch folder: nothing here can run
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(scratch_dir(), ec);
    });
    return std::filesystem::path(pattern);
  }();
  return dir;
}

}  // namespace fuzz
