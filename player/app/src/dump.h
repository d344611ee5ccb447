#pragma once
// What `render --dump` writes for a view, shared by the 2D and the light field commands: the AO
// before and after the blur, the visible surface's world position, normal and depth as float EXRs.
#include "render/programs.h"
#include "render/readback.h"
#include "render/view_targets.h"

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include <string>

namespace app {

// ao_raw.exr, ao_blurred.exr, position.exr, normal.exr and depth.exr at `prefix` (a folder and "/").
bool write_view_exrs(const std::string& prefix, const render::Programs& programs, const render::ViewTargets& targets,
                     const render::WorldSurface& surface, std::string& error);
// Column-major: element c is column c.
nlohmann::json matrix_json(const glm::dmat4& m);
bool write_json(const std::string& path, const nlohmann::json& doc, std::string& error);

}  // namespace app
