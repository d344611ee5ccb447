#include "dump.h"

#include "image_io.h"

#include <fstream>
#include <iomanip>

namespace app {

bool write_view_exrs(const std::string& prefix, const render::Programs& programs, const render::ViewTargets& targets,
                     const render::WorldSurface& surface, std::string& error) {
  const int w = targets.settings().width, h = targets.settings().height;
  // At half resolution the raw AO is smaller; each pixel takes the AO texel of its 2x2 block.
  const std::vector<glm::vec2> raw_low = render::read_ao(targets.ao_raw, targets.ao_width(), targets.ao_height());
  const std::vector<glm::vec2> shaded = render::read_ao_full(programs, targets);
  const int shift = targets.settings().ao_settings.half_resolution ? 1 : 0;
  std::vector<float> raw(static_cast<size_t>(w) * static_cast<size_t>(h)), blurred(raw.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = static_cast<size_t>(y) * static_cast<size_t>(w) + static_cast<size_t>(x);
      raw[i] =
          raw_low[static_cast<size_t>(y >> shift) * static_cast<size_t>(targets.ao_width()) + static_cast<size_t>(x >> shift)].x;
      blurred[i] = shaded[i].x;
    }
  return write_exr(prefix + "ao_raw.exr", w, h, 1, raw, {"Y"}, error) &&
         write_exr(prefix + "ao_blurred.exr", w, h, 1, blurred, {"Y"}, error) &&
         write_exr(prefix + "position.exr", w, h, 4, surface.position, {"R", "G", "B", "A"}, error) &&
         write_exr(prefix + "normal.exr", w, h, 4, surface.normal, {"R", "G", "B", "A"}, error) &&
         write_exr(prefix + "depth.exr", w, h, 1, surface.depth, {"Y"}, error);
}

nlohmann::json matrix_json(const glm::dmat4& m) {
  nlohmann::json columns = nlohmann::json::array();
  for (int c = 0; c < 4; ++c) columns.push_back({m[c][0], m[c][1], m[c][2], m[c][3]});
  return columns;
}

bool write_json(const std::string& path, const nlohmann::json& doc, std::string& error) {
  std::ofstream json(path);
  json << std::setw(2) << doc << "\n";
  if (!json) error = path + ": cannot write";
  return static_cast<bool>(json);
}

}  // namespace app
