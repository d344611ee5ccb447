#pragma once
// One GL context and what belongs to it: the platform that made it, its entry points, what it can
// do, the debug log and the programs compiled in it. Every command, the GL tests and the tools open
// one the same way; when it goes, its programs go first, while their context still exists.
#include "gl/caps.h"
#include "gl/objects.h"
#include "gl/program.h"
#include "gl/program_store.h"
#include "platform/platform.h"

#include <cstddef>
#include <functional>
#include <initializer_list>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace gl {

// Programs compiled once per context and shared by everything drawn in it: two renderers, or a
// renderer and a light field output, that ask for the same stages and defines get the same program.
class ProgramCache {
 public:
  // The program of `stages` with `defines` (whole "#define NAME VALUE\n" lines), compiled on the first
  // request. Null on failure, with the file, the variant and the driver's log in `error`; a failed
  // variant is not kept, so a later request reports the same error again.
  const Program* get(std::initializer_list<Stage> stages, const std::string& defines, std::string& error);
  // The same for whole stage texts (tests give their own).
  const Program* get(const std::vector<StageSource>& sources, std::string& error);

  // From now on, programs not yet in this context are first looked for in `store`, and the ones
  // compiled are kept there.
  void use_store(std::unique_ptr<ProgramStore> store) { store_ = std::move(store); }
  const ProgramStore* store() const { return store_.get(); }
  // The first failure to keep a program in the store ("" if none): the player goes on without it.
  const std::string& store_problem() const { return store_problem_; }

  // How many programs were compiled and linked in this context (a request answered from the cache
  // compiles nothing, nor does a program loaded from the store).
  std::size_t compiled() const { return compiled_; }

 private:
  const Program* add(std::string key, const std::vector<StageSource>& sources, std::string& error);

  std::size_t compiled_ = 0;
  std::unique_ptr<ProgramStore> store_;
  std::string store_problem_;
  // Pointers handed out stay valid: map nodes do not move.
  std::map<std::string, Program, std::less<>> programs_;
};

class Session {
 public:
  // platform::create, the entry points, the caps, and KHR_debug messages to stderr (always in debug
  // builds; in release builds only with `debug_log`). Null and why.
  static std::unique_ptr<Session> open(const platform::Options& options, std::string& error, bool debug_log = false);

  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  platform::Platform& platform() { return *platform_; }
  const platform::Platform& platform() const { return *platform_; }
  const Caps& caps() const { return caps_; }
  ProgramCache& programs() { return programs_; }

 private:
  Session() = default;
  std::unique_ptr<platform::Platform> platform_;
  Caps caps_;
  ProgramCache programs_;  // after platform_: destroyed before the context is
};

}  // namespace gl
