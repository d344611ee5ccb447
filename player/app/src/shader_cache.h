#pragma once
// Where compiled shaders are kept between runs: the driver's own cache (Mesa's) and the player's
// program binaries, both under one folder, so that a restart skips compiling (a board's first
// frame otherwise waits for every shader variant).
#include "gl/session.h"

#include <string>

namespace app {

// The folder `--shader-cache` names: the option itself, nothing for "off", and by default
// $CACHE_DIRECTORY/shaders (systemd's CacheDirectory=), else $XDG_CACHE_HOME/ssao-player/shaders,
// else ~/.cache/ssao-player/shaders.
std::string shader_cache_dir(const std::string& option);

// Before the GL driver loads: Mesa's cache in DIR/mesa, or off when `dir` is empty so that a cold
// start can be measured. A MESA_SHADER_CACHE_* variable already set wins. Returns "" or why DIR/mesa
// could not be made (Mesa then keeps its default).
std::string prepare_driver_cache(const std::string& dir);

// After the context exists: its programs are looked for in, and kept in, DIR/programs, and prepared
// lighting environments in DIR/environments (none kept when `dir` is empty). Returns a line for the
// log that says where, or why not.
std::string open_program_store(gl::Session& session, const std::string& dir);

// "N compiled, M loaded from DIR" (and the rejected files and a failure to save, if any).
std::string program_counts(const gl::ProgramCache& programs);
// "N prepared, M loaded from DIR/environments": the lighting environments of this process so far.
std::string environment_counts();

}  // namespace app
