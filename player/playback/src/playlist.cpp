#include "playback/playlist.h"

#include "base/parse.h"
#include "base/read_file.h"

#include <toml++/toml.h>
#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>

namespace playback {

namespace fs = std::filesystem;

namespace {

// One table per enum: the parser, the "expected" text and name() all read it.
template <class E>
struct Named {
  std::string_view name;
  E value;
};
constexpr std::array<Named<Motion>, 4> motion_names{
    {{"still", Motion::still}, {"turntable", Motion::turntable}, {"orbit", Motion::orbit}, {"file", Motion::file}}};
constexpr std::array<Named<Schedule>, 2> schedule_names{
    {{"sequential", Schedule::sequential}, {"wallclock", Schedule::wallclock}}};

template <class E, std::size_t N>
std::string one_of(const std::array<Named<E>, N>& names) {
  std::string s = "one of ";
  for (std::size_t i = 0; i < N; ++i) s += (i ? ", " : "") + std::string(names[i].name);
  return s;
}

std::string format_number(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

// Keeps messages on one line whatever a string holds.
std::string escape(std::string_view s) {
  std::string out;
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\')
      out += {'\\', c};
    else if (c == '\n')
      out += "\\n";
    else if (c == '\t')
      out += "\\t";
    else if (u < 0x20 || u == 0x7f) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", u);
      out += buf;
    } else
      out += c;
  }
  return out;
}
std::string quote(std::string_view s) {
  return "\"" + escape(s) + "\"";
}

// What a node is, for "got ...": its value for scalars, its type otherwise.
std::string describe(const toml::node& n) {
  if (auto s = n.as_string()) return quote(s->get());
  if (auto i = n.as_integer()) return std::to_string(i->get());
  if (auto f = n.as_floating_point()) return format_number(f->get());
  if (auto b = n.as_boolean()) return b->get() ? "true" : "false";
  if (n.is_table()) return "a table";
  if (auto a = n.as_array()) return a->empty() ? "an empty array" : "an array of " + std::to_string(a->size());
  if (n.is_date()) return "a date";
  if (n.is_time()) return "a time";
  if (n.is_date_time()) return "a date-time";
  return "nothing";
}

// What a node's type is, for "got ..." after a type mismatch.
std::string type_of(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a floating-point number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    case toml::node_type::none:
      return "nothing";
  }
  return "nothing";
}

// The parse of one file. Every check returns false after filling `error`; the first error wins.
class Parser {
 public:
  Parser(std::string source, std::string& error) : source_(std::move(source)), error_(error) {}

  bool fail(const toml::source_region& where, const std::string& field, const std::string& expected, const std::string& got) {
    error_ = source_ + ":" + std::to_string(where.begin.line) + ":" + std::to_string(where.begin.column) + ": " + field +
             ": expected " + expected + ", got " + got;
    return false;
  }

  // Rejects the first key (in file order) that is not in `known`.
  bool known_keys(const toml::table& t, const std::string& prefix, std::initializer_list<std::string_view> known) {
    const toml::key* first = nullptr;
    for (auto&& [k, v] : t) {
      (void)v;
      if (std::find(known.begin(), known.end(), k.str()) != known.end()) continue;
      if (!first || before(k.source(), first->source())) first = &k;
    }
    if (!first) return true;
    std::string list = "one of ";
    for (auto it = known.begin(); it != known.end(); ++it) list += (it == known.begin() ? "" : ", ") + std::string(*it);
    return fail(first->source(), prefix + escape(first->str()), list, "an unknown key");
  }

  static bool before(const toml::source_region& a, const toml::source_region& b) {
    return a.begin.line != b.begin.line ? a.begin.line < b.begin.line : a.begin.column < b.begin.column;
  }

  bool boolean(const toml::table& t, const std::string& prefix, std::string_view key, bool& out) {
    const toml::node* n = t.get(key);
    if (!n) return true;
    if (!n->is_boolean()) return fail(n->source(), prefix + std::string(key), "true or false", type_of(*n));
    out = n->as_boolean()->get();
    return true;
  }

  // A number (integer or float) that `ok` accepts; `what` is the expected text. `negative`, if
  // given, replaces it for negative values.
  template <class Ok>
  bool number(const toml::node& n, const std::string& field, const std::string& what, Ok ok, double& out,
              const std::string& negative = {}) {
    double v{};
    if (auto i = n.as_integer())
      v = static_cast<double>(i->get());
    else if (auto f = n.as_floating_point())
      v = f->get();
    else
      return fail(n.source(), field, what, type_of(n));
    if (!std::isfinite(v) || !ok(v)) return fail(n.source(), field, v < 0 && !negative.empty() ? negative : what, describe(n));
    out = v;
    return true;
  }
  template <class Ok>
  bool number(const toml::table& t, const std::string& prefix, std::string_view key, const std::string& what, Ok ok, double& out,
              const std::string& negative = {}) {
    const toml::node* n = t.get(key);
    return !n || number(*n, prefix + std::string(key), what, ok, out, negative);
  }

  template <class E, std::size_t N>
  bool choice(const toml::table& t, const std::string& prefix, std::string_view key, const std::array<Named<E>, N>& names,
              E& out) {
    const toml::node* n = t.get(key);
    if (!n) return true;
    if (auto s = n->as_string()) {
      for (const auto& e : names)
        if (e.name == s->get()) {
          out = e.value;
          return true;
        }
      return fail(n->source(), prefix + std::string(key), one_of(names), describe(*n));
    }
    return fail(n->source(), prefix + std::string(key), one_of(names), type_of(*n));
  }

  const toml::table* table(const toml::table& t, const std::string& prefix, std::string_view key, const std::string& what,
                           bool& ok) {
    const toml::node* n = t.get(key);
    if (!n) return nullptr;
    if (!n->is_table()) ok = fail(n->source(), prefix + std::string(key), what, type_of(*n));
    return n->as_table();
  }

  const std::string& source() const { return source_; }

 private:
  std::string source_;
  std::string& error_;
};

// Paths: relative to the playlist's folder, normalised, symlinks of the existing part resolved,
// and then required to lie inside the content root.
struct Paths {
  fs::path folder, root;

  static fs::path real(const fs::path& p) {
    std::error_code ec;
    fs::path r = fs::weakly_canonical(p, ec);
    return ec ? p : r;
  }
  static fs::path absolute(const fs::path& p) {
    std::error_code ec;
    fs::path a = fs::absolute(p, ec);
    return (ec ? p : a).lexically_normal();
  }
  static bool inside(const fs::path& p, const fs::path& root) {
    auto it = p.begin();
    for (const auto& part : root) {
      if (part.empty()) continue;  // a trailing separator
      if (it == p.end() || *it != part) return false;
      ++it;
    }
    return true;
  }
  static std::string trimmed(const fs::path& p) {
    std::string s = p.string();
    while (s.size() > 1 && s.back() == '/') s.pop_back();
    return s;
  }
};

bool read_path(Parser& p, const Paths& paths, const toml::node& n, const std::string& field, bool allow_builtin,
               std::string& out) {
  const std::string what = allow_builtin ? "a path or builtin:NAME" : "a path";
  const auto* s = n.as_string();
  if (!s) return p.fail(n.source(), field, what, type_of(n));
  const std::string& raw = s->get();
  if (allow_builtin && raw.rfind("builtin:", 0) == 0) {
    if (raw.size() == 8) return p.fail(n.source(), field, "a name after builtin:", describe(n));
    out = raw;
    return true;
  }
  if (raw.empty()) return p.fail(n.source(), field, what, "an empty string");
  const fs::path given(raw);
  const fs::path resolved = Paths::real((given.is_absolute() ? given : paths.folder / given).lexically_normal());
  if (!Paths::inside(resolved, paths.root))
    return p.fail(n.source(), field, "a path inside the content root " + Paths::trimmed(paths.root),
                  describe(n) + " (resolves to " + quote(resolved.string()) + ")");
  out = resolved.string();
  return true;
}

bool read_background(Parser& p, const toml::node& n, const std::string& field, glm::vec3& out) {
  const std::string what = "an array of 3 numbers in [0, 1] or a \"#rrggbb\" string";
  if (const auto* s = n.as_string()) {
    const std::string& v = s->get();
    const bool ok = v.size() == 7 && v[0] == '#' &&
                    std::all_of(v.begin() + 1, v.end(), [](char c) { return std::isxdigit(static_cast<unsigned char>(c)); });
    if (!ok) return p.fail(n.source(), field, what, describe(n));
    for (int i = 0; i < 3; ++i) {
      int byte = 0;
      base::parse_int(std::string_view(v).substr(1 + 2 * i, 2), 0, 255, byte, 16);  // hex digits: checked above
      out[i] = static_cast<float>(byte) / 255.0f;
    }
    return true;
  }
  const auto* a = n.as_array();
  if (!a) return p.fail(n.source(), field, what, type_of(n));
  if (a->size() != 3) return p.fail(n.source(), field, what, describe(n));
  for (std::size_t i = 0; i < 3; ++i) {
    double v{};
    if (!p.number(
            *a->get(i), field + "[" + std::to_string(i) + "]", "a number in [0, 1]", [](double x) { return x >= 0 && x <= 1; },
            v))
      return false;
    out[static_cast<int>(i)] = static_cast<float>(v);
  }
  return true;
}

bool read_keys(Parser& p, const toml::table& cam, const std::string& prefix, double duration, CameraPath& c) {
  const toml::node* n = cam.get("keys");
  const std::string field = prefix + "keys";
  const std::string what = "an array of at least 2 tables { t = ..., azimuth = ..., elevation = ..., distance = ... }";
  if (c.motion != Motion::orbit) {
    if (n) return p.fail(n->source(), field, "keys only with motion = \"orbit\"", describe(*n));
    return true;
  }
  if (!n) return p.fail(cam.source(), field, "at least 2 keys for motion \"orbit\"", "nothing");
  const auto* a = n->as_array();
  if (!a) return p.fail(n->source(), field, what, type_of(*n));
  if (!a->empty() && !a->is_array_of_tables()) return p.fail(n->source(), field, what, "an array of non-tables");
  if (a->size() < 2) return p.fail(n->source(), field, "at least 2 keys", describe(*n));
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::table& kt = *a->get(i)->as_table();
    const std::string kp = field + "[" + std::to_string(i) + "].";
    if (!p.known_keys(kt, kp, {"t", "azimuth", "elevation", "distance"})) return false;
    OrbitKey k{.azimuth_deg = c.azimuth_deg, .elevation_deg = c.elevation_deg, .distance = c.distance};
    const toml::node* t = kt.get("t");
    if (!t) return p.fail(kt.source(), kp + "t", "a time in seconds", "nothing");
    if (i == 0) {
      if (!p.number(
              *t, kp + "t", "0 (the first key is the item's start)", [](double v) { return v == 0; }, k.t))
        return false;
    } else if (const double prev = c.keys.back().t; !p.number(
                   *t, kp + "t", "a time after the previous key's " + format_number(prev), [&](double v) { return v > prev; },
                   k.t)) {
      return false;
    } else if (k.t > duration) {
      return p.fail(t->source(), kp + "t", "a time within the item's " + format_number(duration) + " s", describe(*t));
    }
    if (!p.number(
            kt, kp, "azimuth", "degrees", [](double) { return true; }, k.azimuth_deg) ||
        !p.number(
            kt, kp, "elevation", "degrees in [-89, 89]", [](double v) { return v >= -89 && v <= 89; }, k.elevation_deg) ||
        !p.number(
            kt, kp, "distance", "a multiple of the fitting distance > 0", [](double v) { return v > 0; }, k.distance))
      return false;
    c.keys.push_back(k);
  }
  return true;
}

// motion = "file": `index` picks the scene's camera (0 when absent); only with that motion.
bool read_file_camera(Parser& p, const toml::table& t, const std::string& prefix, CameraPath& c) {
  const toml::node* n = t.get("index");
  if (!n) return true;
  const std::string field = prefix + "index";
  if (c.motion != Motion::file) return p.fail(n->source(), field, "index only with motion = \"file\"", describe(*n));
  const auto* i = n->as_integer();
  if (!i || i->get() < 0 || i->get() > 1000000)
    return p.fail(n->source(), field, "a camera index of the scene, 0 or more", describe(*n));
  c.index = static_cast<int>(i->get());
  return true;
}

bool read_camera(Parser& p, const toml::table& t, const std::string& prefix, double duration, CameraPath& c) {
  if (!p.known_keys(t, prefix, {"motion", "period", "elevation", "distance", "azimuth", "fov", "keys", "index"})) return false;
  return p.choice(t, prefix, "motion", motion_names, c.motion) && read_file_camera(p, t, prefix, c) &&
         p.number(
             t, prefix, "period", "seconds per turn > 0", [](double v) { return v > 0; }, c.period_s,
             "seconds per turn > 0 (a negative period is not supported)") &&
         p.number(
             t, prefix, "elevation", "degrees in [-89, 89]", [](double v) { return v >= -89 && v <= 89; }, c.elevation_deg) &&
         p.number(
             t, prefix, "distance", "a multiple of the fitting distance > 0", [](double v) { return v > 0; }, c.distance) &&
         p.number(
             t, prefix, "azimuth", "degrees", [](double) { return true; }, c.azimuth_deg) &&
         p.number(
             t, prefix, "fov", "degrees in (1, 170)", [](double v) { return v > 1 && v < 170; }, c.fov_deg) &&
         read_keys(p, t, prefix, duration, c);
}

bool read_settings(Parser& p, const toml::table& t, const std::string& prefix, const SettingValidator& validate,
                   std::vector<Setting>& out) {
  std::vector<std::pair<const toml::key*, const toml::node*>> entries;
  for (auto&& [k, v] : t) entries.emplace_back(&k, &v);
  std::sort(entries.begin(), entries.end(),
            [](const auto& a, const auto& b) { return Parser::before(a.first->source(), b.first->source()); });
  for (const auto& [k, v] : entries) {
    const std::string field = prefix + escape(k->str());
    std::string value;
    if (auto s = v->as_string())
      value = s->get();
    else if (auto i = v->as_integer())
      value = std::to_string(i->get());
    else if (auto f = v->as_floating_point())
      value = format_number(f->get());
    else if (auto b = v->as_boolean())
      value = b->get() ? "on" : "off";
    else
      return p.fail(v->source(), field, "a string, integer, float or boolean", type_of(*v));
    if (validate) {
      std::string why;
      if (!validate(k->str(), value, why)) {
        if (why.empty()) why = "expected a valid value";
        if (why.rfind("expected ", 0) == 0) why.erase(0, 9);
        return p.fail(v->source(), field, why, describe(*v));
      }
    }
    out.push_back({std::string(k->str()), std::move(value)});
  }
  return true;
}

bool read_item(Parser& p, const Paths& paths, const ParseOptions& options, const toml::table& t, std::size_t index, Item& item) {
  const std::string prefix = "item[" + std::to_string(index) + "].";
  item.line = static_cast<int>(t.source().begin.line);
  if (!p.known_keys(
          t, prefix,
          {"scene", "duration", "camera", "ao", "background", "display", "environment", "animation", "animation_speed"}))
    return false;
  const toml::node* scene = t.get("scene");
  if (!scene) return p.fail(t.source(), prefix + "scene", "a path or builtin:NAME", "nothing");
  if (!read_path(p, paths, *scene, prefix + "scene", true, item.scene)) return false;
  if (!p.number(
          t, prefix, "duration", "a number of seconds > 0", [](double v) { return v > 0; }, item.duration_s))
    return false;
  bool ok = true;
  if (const auto* cam = p.table(t, prefix, "camera", "a table", ok)) {
    if (!read_camera(p, *cam, prefix + "camera.", item.duration_s, item.camera)) return false;
  }
  if (!ok) return false;
  if (const auto* ao = p.table(t, prefix, "ao", "a table of render settings", ok)) {
    if (!read_settings(p, *ao, prefix + "ao.", options.validate_setting, item.settings)) return false;
  }
  if (!ok) return false;
  if (const toml::node* bg = t.get("background")) {
    if (!read_background(p, *bg, prefix + "background", item.background)) return false;
    item.has_background = true;
  }
  if (const toml::node* d = t.get("display")) {
    if (!read_path(p, paths, *d, prefix + "display", false, item.display)) return false;
  }
  if (const toml::node* a = t.get("animation")) {
    // Which animation is checked against the scene once it is loaded; here only its form.
    if (const auto number = a->as_integer()) {
      if (number->get() < 0)
        return p.fail(a->source(), prefix + "animation", "\"all\", \"none\", a name or an index >= 0", describe(*a));
      item.animation = std::to_string(number->get());
    } else if (const auto name = a->as_string()) {
      if (name->get().empty())
        return p.fail(a->source(), prefix + "animation", "\"all\", \"none\", a name or an index >= 0", "\"\"");
      item.animation = name->get();
    } else {
      return p.fail(a->source(), prefix + "animation", "\"all\", \"none\", a name or an index >= 0", type_of(*a));
    }
  }
  if (!p.number(
          t, prefix, "animation_speed", "a number >= 0 (1: as authored, 0: held at the start)", [](double v) { return v >= 0; },
          item.animation_speed))
    return false;
  item.environment = options.default_environment;
  if (const toml::node* e = t.get("environment")) {
    if (!read_path(p, paths, *e, prefix + "environment", true, item.environment)) return false;
    if (item.environment.rfind("builtin:", 0) == 0 && item.environment != "builtin:studio")
      return p.fail(e->source(), prefix + "environment", "a path or builtin:studio", describe(*e));
  }
  return true;
}

bool parse(std::string_view text, const std::string& source_path, const ParseOptions& options, Playlist& out,
           std::string& error) {
  toml::table root;
  try {
    root = toml::parse(text, std::string_view(source_path));
  } catch (const toml::parse_error& e) {
    error = source_path + ":" + std::to_string(e.source().begin.line) + ":" + std::to_string(e.source().begin.column) + ": " +
            std::string(e.description());
    return false;
  }
  Parser p(source_path, error);
  Paths paths;
  fs::path folder = fs::path(source_path).parent_path();
  if (folder.empty()) folder = ".";
  paths.folder = Paths::absolute(folder);
  paths.root = Paths::real(options.content_root.empty() ? paths.folder : Paths::absolute(options.content_root));

  Playlist pl;
  pl.source = source_path;
  if (!p.known_keys(root, "", {"loop", "shuffle", "seed", "fade", "schedule", "item"}) || !p.boolean(root, "", "loop", pl.loop) ||
      !p.boolean(root, "", "shuffle", pl.shuffle))
    return false;
  if (const toml::node* n = root.get("seed")) {
    const auto* i = n->as_integer();
    if (!i) return p.fail(n->source(), "seed", "an integer >= 0", type_of(*n));
    if (i->get() < 0) return p.fail(n->source(), "seed", "an integer >= 0", describe(*n));
    pl.seed = static_cast<std::uint64_t>(i->get());
  }
  if (!p.number(
          root, "", "fade", "a number of seconds >= 0", [](double v) { return v >= 0; }, pl.fade_s) ||
      !p.choice(root, "", "schedule", schedule_names, pl.schedule))
    return false;
  const toml::node* items = root.get("item");
  const std::string what = "at least one [[item]] table";
  if (!items) return p.fail(root.source(), "item", what, "nothing");
  const auto* a = items->as_array();
  if (!a) return p.fail(items->source(), "item", what, type_of(*items));
  if (a->empty()) return p.fail(items->source(), "item", what, "an empty array");
  if (!a->is_array_of_tables()) return p.fail(items->source(), "item", what, "an array of non-tables");
  for (std::size_t i = 0; i < a->size(); ++i) {
    Item item;
    if (!read_item(p, paths, options, *a->get(i)->as_table(), i, item)) return false;
    pl.items.push_back(std::move(item));
  }
  out = std::move(pl);
  return true;
}

}  // namespace

std::string_view name(Motion m) {
  for (const auto& e : motion_names)
    if (e.value == m) return e.name;
  return "?";
}

std::string_view name(Schedule s) {
  for (const auto& e : schedule_names)
    if (e.value == s) return e.name;
  return "?";
}

bool parse_playlist(std::string_view toml_text, const std::string& source_path, const ParseOptions& options, Playlist& out,
                    std::string& error) {
  try {
    return parse(toml_text, source_path, options, out, error);
  } catch (const std::exception& e) {  // allocation failures and the like; a validator's own throws
    error = source_path + ": " + e.what();
    return false;
  }
}

bool load_playlist(const std::string& path, const ParseOptions& options, Playlist& out, std::string& error) {
  try {
    std::string text;
    if (!base::read_regular_file(path, "playlist", kMaxPlaylistBytes, text, error)) return false;
    return parse_playlist(text, path, options, out, error);
  } catch (const std::exception& e) {
    error = path + ": " + e.what();
    return false;
  }
}

Playlist playlist_from_scenes(const std::vector<std::string>& scenes, double duration_s, double period_s) {
  Playlist pl;
  pl.source = "command line";
  for (const auto& s : scenes) {
    Item item;
    item.scene = s;
    item.duration_s = duration_s;
    item.camera.period_s = period_s;
    pl.items.push_back(std::move(item));
  }
  return pl;
}

}  // namespace playback
