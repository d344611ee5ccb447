#pragma once
// Display description files (TOML): `type = "modules"` (HoloVizio style, see modules.h) or
// `type = "quilt"` (Looking Glass style, naming the vendor's visual.json, see quilt.h). docs/light-field.md
// lists every key.
//
// Errors: functions return false and `error` says "FILE:LINE:COLUMN: KEY: expected ..., got ...";
// nothing throws.
#include "lightfield/modules.h"
#include "lightfield/quilt.h"

#include <cstddef>
#include <string>
#include <string_view>

namespace lightfield {

enum class DisplayType { modules, quilt };

struct Display {
  DisplayType type = DisplayType::modules;
  ModulesDisplay modules;        // when type is modules
  QuiltDisplay quilt;            // when type is quilt
  std::string calibration_path;  // quilt: the visual.json read, resolved against the display file's folder
  int views() const { return type == DisplayType::modules ? static_cast<int>(modules.module_x.size()) : quilt.views(); }
};

// Reads and validates `path`; a quilt's calibration file is read too.
// The largest display file and calibration (visual.json) read, in bytes; a FIFO, a device or a
// folder is refused too (base/read_file.h).
inline constexpr std::size_t kMaxDisplayFileBytes = 1u << 20;

bool load_display(const std::string& path, Display& out, std::string& error);
// The same from text: `path` names it in errors and locates the calibration file.
bool parse_display(std::string_view text, const std::string& path, Display& out, std::string& error);
// visual.json: each field an object such as "pitch": {"value": 49.96}. `source` names it in errors.
bool parse_calibration(std::string_view text, const std::string& source, Calibration& out, std::string& error);

}  // namespace lightfield
