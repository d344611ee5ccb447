#pragma once
// `player render SCENE --display FILE`: every module or quilt view of a light field display.
#include "app/render_command.h"
#include "gl/session.h"

#include <iosfwd>
#include <memory>
#include <string>

namespace app {

// The context `render`, `render --display` and `info` draw in, on `platform` with a surface of
// `width` x `height`; null after "error: ..." on `err`. Its shaders are cached in `shader_cache`
// (--shader-cache: a folder, "off", or "" for the default; shader_cache.h).
std::unique_ptr<gl::Session> open_render_session(const std::string& platform, int width, int height, std::ostream& err,
                                                 const std::string& shader_cache = "");

int run_render_light_field(const RenderOptions& options, std::ostream& out, std::ostream& err);

}  // namespace app
