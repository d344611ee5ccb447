#pragma once
// `player render SCENE --display FILE`: every module or quilt view of a light field display.
#include "app/render_command.h"

#include <iosfwd>

namespace app {

int run_render_light_field(const RenderOptions& options, std::ostream& out, std::ostream& err);

}  // namespace app
