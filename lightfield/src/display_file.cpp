#include "lightfield/display_file.h"

#include "base/parse.h"
#include "base/read_file.h"

#include <toml++/toml.h>
#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <sstream>

namespace lightfield {
namespace {

constexpr int kMaxModules = 1024;
constexpr int kMaxImageSide = 16384;
constexpr int kMaxQuiltSide = 64;
// Lengths beyond this (a display a million units wide) are typos, and would overflow the products
// the geometry forms from them.
constexpr double kMaxMagnitude = 1e6;

struct Failure {
  std::string message;
};

std::string type_name(const toml::node& node) {
  std::ostringstream text;
  text << node.type();
  return text.str();
}

std::string describe(const toml::node& node) {
  if (node.is_string()) return "'" + node.as_string()->get() + "'";
  if (node.is_integer()) return std::to_string(node.as_integer()->get());
  if (node.is_floating_point()) {
    // The shortest text that reads back as the same number: 1000000.5 is not 1e+06.
    char text[32];
    const std::to_chars_result end = std::to_chars(text, text + sizeof text, node.as_floating_point()->get());
    return std::string(text, end.ptr);
  }
  return type_name(node);
}

// Typed access to one table whose errors carry the file, line and column, the dotted key and what
// was expected.
class Fields {
 public:
  Fields(const toml::table& table, const std::string& source, std::string prefix)
      : table_(table), source_(source), prefix_(std::move(prefix)) {}

  [[noreturn]] void fail_at(const toml::node* node, const std::string& key, const std::string& expected) const {
    const toml::source_region& where = node != nullptr ? node->source() : table_.source();
    throw Failure{source_ + ":" + std::to_string(where.begin.line) + ":" + std::to_string(where.begin.column) + ": " + prefix_ +
                  key + ": expected " + expected + ", got " + (node != nullptr ? describe(*node) : "nothing")};
  }
  [[noreturn]] void fail(const std::string& key, const std::string& expected) const { fail_at(table_.get(key), key, expected); }

  void only(std::initializer_list<std::string_view> keys) const {
    for (const auto& [key, node] : table_) {
      bool known = false;
      std::string list;
      for (std::string_view name : keys) {
        known = known || key.str() == name;
        list += (list.empty() ? "" : ", ") + std::string(name);
      }
      if (!known)
        throw Failure{source_ + ":" + std::to_string(node.source().begin.line) + ":" +
                      std::to_string(node.source().begin.column) + ": " + prefix_ + std::string(key.str()) +
                      ": unknown key (expected one of " + list + ")"};
    }
  }
  bool has(const std::string& key) const { return table_.get(key) != nullptr; }

  double number(const std::string& key, const double* fallback, const std::string& range, bool (*in_range)(double)) const {
    const toml::node* node = table_.get(key);
    if (node == nullptr) {
      if (fallback == nullptr) fail(key, "a number " + range);
      return *fallback;
    }
    double value = 0.0;
    if (const auto* i = node->as_integer())
      value = static_cast<double>(i->get());
    else if (const auto* f = node->as_floating_point())
      value = f->get();
    else
      fail(key, "a number " + range);
    if (!std::isfinite(value) || !in_range(value)) fail(key, "a number " + range);
    if (std::abs(value) > kMaxMagnitude) fail(key, "a number of magnitude at most 1e6");
    return value;
  }
  long long integer(const std::string& key, long long low, long long high) const {
    const toml::node* node = table_.get(key);
    const toml::value<int64_t>* value = node != nullptr ? node->as_integer() : nullptr;
    if (value == nullptr || value->get() < low || value->get() > high)
      fail(key, "an integer in " + std::to_string(low) + ".." + std::to_string(high));
    return value->get();
  }
  std::string string(const std::string& key) const {
    const toml::node* node = table_.get(key);
    if (node == nullptr || !node->is_string()) fail(key, "a string");
    return node->as_string()->get();
  }
  // "WxH", each side in 1..max.
  glm::ivec2 size(const std::string& key, int max, const std::string& what) const {
    glm::ivec2 out(0);
    if (!base::parse_size(string(key), max, out.x, out.y)) fail(key, what + " as \"WxH\", each 1.." + std::to_string(max));
    return out;
  }
  std::vector<double> numbers(const std::string& key, size_t min_count, size_t max_count, const std::string& expected) const {
    const toml::node* node = table_.get(key);
    const toml::array* array = node != nullptr ? node->as_array() : nullptr;
    if (array == nullptr || array->size() < min_count || array->size() > max_count) fail(key, expected);
    std::vector<double> out;
    for (const toml::node& element : *array) {
      double value = 0.0;
      if (const auto* i = element.as_integer())
        value = static_cast<double>(i->get());
      else if (const auto* f = element.as_floating_point())
        value = f->get();
      else
        fail_at(&element, key, expected);
      if (!std::isfinite(value) || std::abs(value) > kMaxMagnitude)
        fail_at(&element, key, expected + ", each of magnitude at most 1e6");
      out.push_back(value);
    }
    return out;
  }
  glm::dvec3 point(const std::string& key) const {
    const std::vector<double> v = numbers(key, 3, 3, "three numbers [x, y, z]");
    return {v[0], v[1], v[2]};
  }
  const Fields table(const std::string& key, bool required) const {
    const toml::node* node = table_.get(key);
    if (node == nullptr) {
      if (required) fail(key, "a table [" + prefix_ + key + "]");
      return Fields(empty_, source_, prefix_ + key + ".");
    }
    if (!node->is_table()) fail(key, "a table [" + prefix_ + key + "]");
    return Fields(*node->as_table(), source_, prefix_ + key + ".");
  }
  const toml::node* node(const std::string& key) const { return table_.get(key); }

 private:
  static inline const toml::table empty_{};
  const toml::table& table_;
  const std::string& source_;
  std::string prefix_;
};

bool positive(double v) {
  return v > 0.0;
}
bool negative(double v) {
  return v < 0.0;
}
bool any(double) {
  return true;
}

// `out` is a fresh ModulesDisplay: parse_display starts from Display{}.
void read_modules(const Fields& top, ModulesDisplay& out) {
  top.only({"type", "screen", "observer", "modules", "roi"});
  const Fields screen = top.table("screen", true);
  screen.only({"width", "height"});
  out.screen_width = screen.number("width", nullptr, "> 0", positive);
  out.screen_height = screen.number("height", nullptr, "> 0", positive);

  const Fields observer = top.table("observer", true);
  observer.only({"distance", "height"});
  out.observer_distance = observer.number("distance", nullptr, "> 0 (the observer line's distance from the screen)", positive);
  out.observer_height = observer.number("height", &out.observer_height, "(the observer line's height)", any);

  const Fields modules = top.table("modules", true);
  modules.only({"count", "x_first", "x_last", "x", "z", "resolution", "footprint"});
  out.module_z = modules.number("z", nullptr, "< 0 (the modules stand behind the screen)", negative);
  if (modules.has("x")) {
    out.module_x = modules.numbers("x", 1, kMaxModules, "1.." + std::to_string(kMaxModules) + " numbers, one x per module");
    if (modules.has("count") && modules.integer("count", 1, kMaxModules) != static_cast<long long>(out.module_x.size()))
      modules.fail("count", "the number of entries of modules.x (" + std::to_string(out.module_x.size()) + ")");
    if (modules.has("x_first") || modules.has("x_last"))
      modules.fail(modules.has("x_first") ? "x_first" : "x_last", "nothing when modules.x lists the positions");
  } else {
    const long long count = modules.integer("count", 1, kMaxModules);
    const double first = modules.number("x_first", nullptr, "(the first module's x)", any);
    const double last = modules.number("x_last", nullptr, "(the last module's x)", any);
    if (count == 1 && first != last) modules.fail("x_last", "x_first when there is one module");
    for (long long k = 0; k < count; ++k)  // both ends at most 1e6: every position is finite
      out.module_x.push_back(count == 1 ? first
                                        : first + (last - first) * static_cast<double>(k) / static_cast<double>(count - 1));
  }
  const glm::ivec2 resolution = modules.size("resolution", kMaxImageSide, "each module's image size");
  out.width = resolution.x;
  out.height = resolution.y;
  // Every module's image goes into one montage texture: its size is checked here, before anything
  // is allocated, rather than found out by the GPU as an incomplete framebuffer.
  const glm::ivec2 grid = montage_grid(static_cast<int>(out.module_x.size()));
  const long long montage_width = static_cast<long long>(grid.x) * resolution.x;
  const long long montage_height = static_cast<long long>(grid.y) * resolution.y;
  if (montage_width > kMaxImageSide || montage_height > kMaxImageSide)
    modules.fail("resolution", "a montage of at most " + std::to_string(kMaxImageSide) +
                                   " pixels per side: " + std::to_string(out.module_x.size()) + " modules of this size make " +
                                   std::to_string(montage_width) + "x" + std::to_string(montage_height) + " (" +
                                   std::to_string(grid.x) + "x" + std::to_string(grid.y) + " modules)");
  out.footprint = {-out.screen_width * 0.5, out.screen_width * 0.5};
  if (modules.has("footprint")) {
    const std::vector<double> f = modules.numbers("footprint", 2, 2, "two numbers [x0, x1] with x0 < x1");
    if (!(f[0] < f[1])) modules.fail("footprint", "two numbers [x0, x1] with x0 < x1");
    out.footprint = {f[0], f[1]};
  }

  const Fields roi = top.table("roi", false);
  roi.only({"world_min", "world_max", "physical_min", "physical_max"});
  if (roi.has("world_min") || roi.has("world_max")) {
    Box world{roi.point("world_min"), roi.point("world_max")};
    if (!glm::all(glm::lessThan(world.min, world.max))) roi.fail("world_max", "a point above roi.world_min on every axis");
    out.world_roi = world;
  }
  // Default: the screen's rectangle, as deep as a quarter of its smaller side on each side of it.
  const double depth = std::min(out.screen_width, out.screen_height) * 0.25;
  out.physical_roi = {{-out.screen_width * 0.5, -out.screen_height * 0.5, -depth},
                      {out.screen_width * 0.5, out.screen_height * 0.5, depth}};
  if (roi.has("physical_min") || roi.has("physical_max")) {
    out.physical_roi = {roi.point("physical_min"), roi.point("physical_max")};
    if (!glm::all(glm::lessThan(out.physical_roi.min, out.physical_roi.max)))
      roi.fail("physical_max", "a point above roi.physical_min on every axis");
  }
  if (!(out.physical_roi.min.z > out.module_z))
    roi.fail("physical_min", "z above modules.z (" + std::to_string(out.module_z) + "): the box lies in front of the modules");
  if (!(out.physical_roi.max.z < out.observer_distance))
    roi.fail("physical_max", "z below observer.distance (" + std::to_string(out.observer_distance) + ")");
}

void read_quilt(const Fields& top, const std::string& path, Display& out) {
  top.only({"type", "calibration", "quilt", "view_size"});
  const std::string calibration = top.string("calibration");
  const glm::ivec2 grid = top.size("quilt", kMaxQuiltSide, "columns x rows of views");
  const glm::ivec2 view = top.size("view_size", kMaxImageSide, "each view's size");
  if (static_cast<long long>(grid.x) * view.x > kMaxImageSide || static_cast<long long>(grid.y) * view.y > kMaxImageSide)
    top.fail("view_size",
             "a quilt of at most " + std::to_string(kMaxImageSide) + " pixels per side (columns x width, rows x height)");
  out.quilt.columns = grid.x;
  out.quilt.rows = grid.y;
  out.quilt.view_width = view.x;
  out.quilt.view_height = view.y;
  const std::filesystem::path relative(calibration);
  out.calibration_path = relative.is_absolute() ? calibration : (std::filesystem::path(path).parent_path() / relative).string();
  std::string text, error;
  if (!base::read_regular_file(out.calibration_path, "calibration", kMaxDisplayFileBytes, text, error))
    top.fail("calibration", "a readable regular file (" + error + ")");
  if (!parse_calibration(text, out.calibration_path, out.quilt.calibration, error)) throw Failure{error};
}

}  // namespace

bool parse_display(std::string_view text, const std::string& path, Display& out, std::string& error) {
  try {
    const toml::table root = toml::parse(text, path);
    const Fields top(root, path, "");
    const std::string type = top.string("type");
    out = Display{};
    if (type == "modules") {
      out.type = DisplayType::modules;
      read_modules(top, out.modules);
    } else if (type == "quilt") {
      out.type = DisplayType::quilt;
      read_quilt(top, path, out);
    } else {
      top.fail("type", "\"modules\" or \"quilt\"");
    }
    return true;
  } catch (const toml::parse_error& e) {
    error = path + ":" + std::to_string(e.source().begin.line) + ":" + std::to_string(e.source().begin.column) + ": " +
            std::string(e.description());
  } catch (const Failure& failure) {
    error = failure.message;
  }
  return false;
}

bool load_display(const std::string& path, Display& out, std::string& error) {
  std::string text;
  if (!base::read_regular_file(path, "display file", kMaxDisplayFileBytes, text, error)) return false;
  return parse_display(text, path, out, error);
}

bool parse_calibration(std::string_view text, const std::string& source, Calibration& out, std::string& error) {
  const nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) {
    error = source + ": expected a JSON object (the display's visual.json)";
    return false;
  }
  // `fallback`: the value where the file may omit the field; nullptr where it must give it.
  const auto field = [&](const char* key, const double* fallback, double& value, bool (*in_range)(double), const char* range) {
    const auto it = doc.find(key);
    if (it == doc.end()) {
      if (fallback == nullptr) {
        error = source + ": " + key + ": expected an object {\"value\": number " + range + "}, got nothing";
        return false;
      }
      value = *fallback;
      return true;
    }
    const nlohmann::json* number = it->is_object() && it->contains("value") ? &(*it)["value"] : nullptr;
    if (number == nullptr || !number->is_number() || !std::isfinite(number->get<double>()) || !in_range(number->get<double>())) {
      // The type, not the text: dumping a value nested a million deep would recurse that deep.
      std::string got = it->type_name();
      if (number != nullptr)
        got = number->is_number() ? "\"value\": " + number->dump() : std::string("\"value\" of type ") + number->type_name();
      error = source + ": " + key + ": expected an object {\"value\": number " + range + "}, got " + got;
      return false;
    }
    value = number->get<double>();
    return true;
  };
  // Bounded so that the interleave's products (pitch * screenW / DPI, screenH / (screenW * slope)) stay finite.
  const auto pitch = [](double v) { return v > 0.0 && v <= kMaxMagnitude; };
  const auto slope = [](double v) { return std::abs(v) >= 1e-6 && std::abs(v) <= kMaxMagnitude; };
  const auto bounded = [](double v) { return std::abs(v) <= kMaxMagnitude; };
  const auto dpi = [](double v) { return v >= 1.0 && v <= kMaxMagnitude; };
  const auto side = [](double v) { return v >= 1.0 && v <= kMaxImageSide && v == std::floor(v); };
  const auto flag = [](double v) { return v == 0.0 || v == 1.0; };
  const auto cone = [](double v) { return v > 0.0 && v < 180.0; };
  double width = 0.0, height = 0.0, inverted = 0.0, flip_x = 0.0, flip_y = 0.0;
  Calibration c;
  const double off = 0.0, default_cone = c.view_cone_deg;
  if (!field("pitch", nullptr, c.pitch, pitch, "in (0, 1e6]") ||
      !field("slope", nullptr, c.slope, slope, "of magnitude 1e-6..1e6") ||
      !field("center", nullptr, c.center, bounded, "of magnitude at most 1e6") ||
      !field("DPI", nullptr, c.dpi, dpi, "in 1..1e6") || !field("screenW", nullptr, width, side, "(an integer in 1..16384)") ||
      !field("screenH", nullptr, height, side, "(an integer in 1..16384)") ||
      !field("invView", &off, inverted, flag, "(0 or 1)") || !field("flipImageX", &off, flip_x, flag, "(0 or 1)") ||
      !field("flipImageY", &off, flip_y, flag, "(0 or 1)") ||
      !field("viewCone", &default_cone, c.view_cone_deg, cone, "(degrees, in (0, 180))"))
    return false;
  c.screen_width = static_cast<int>(width);
  c.screen_height = static_cast<int>(height);
  c.inverted_views = inverted != 0.0;
  c.flip_x = flip_x != 0.0;
  c.flip_y = flip_y != 0.0;
  out = c;
  return true;
}

}  // namespace lightfield
