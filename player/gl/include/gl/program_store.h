#pragma once
// Linked programs kept on disk between runs (glGetProgramBinary / glProgramBinary), so that a
// restart skips compiling: a board's first frame otherwise waits for every shader variant.
#include "gl/caps.h"
#include "gl/program.h"

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace gl {

class ProgramStore {
 public:
  // The store in `dir` (made if missing) for the current context's driver. Null, with why in
  // `reason`, when the driver offers no binary format or the folder cannot be made. Opening removes
  // the least recently used files beyond kMaxFiles or kMaxBytes.
  static std::unique_ptr<ProgramStore> open(const std::string& dir, const Caps& caps, std::string& reason);

  // The program kept for exactly these stage texts on this driver, or an empty Program. A file that
  // is truncated, damaged, or that the driver refuses is counted in rejected(), removed and never
  // used: the caller compiles instead.
  Program load(const std::vector<StageSource>& sources);
  // Keeps a program linked from `sources` (with the retrievable hint). False with why in `error`;
  // nothing half-written is ever left under the name load reads.
  bool save(const std::vector<StageSource>& sources, const Program& program, std::string& error);

  const std::string& dir() const { return dir_; }
  std::size_t loaded() const { return loaded_; }
  std::size_t rejected() const { return rejected_; }
  // The file a program of these texts is kept in (tests damage it).
  std::string path_for(const std::vector<StageSource>& sources) const;

  static constexpr std::size_t kMaxFiles = 512;
  static constexpr std::size_t kMaxBytes = 64u << 20;

 private:
  ProgramStore() = default;
  std::string dir_;
  std::string driver_;  // vendor, renderer and versions: a driver update makes every file a miss
  std::size_t loaded_ = 0, rejected_ = 0;
};

}  // namespace gl
