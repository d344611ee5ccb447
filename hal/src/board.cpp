#include "hal/board.h"

#include "base/names.h"
#include "base/read_file.h"

#include <toml++/toml.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <initializer_list>
#include <map>
#include <sstream>
#include <string_view>

namespace hal {

std::string GpioLine::describe() const {
  std::string s = line_name.empty() ? chip + ":" + std::to_string(offset) : "line " + line_name;
  if (!line_name.empty() && !chip.empty()) s += " on " + chip;
  return s;
}

namespace {

constexpr base::Name<Action> kActionNames[] = {
    {Action::none, "none"}, {Action::next, "next"},     {Action::previous, "previous"}, {Action::pause, "pause"},
    {Action::ao, "ao"},     {Action::output, "output"}, {Action::restart, "restart"},   {Action::check, "check"}};
static_assert(base::in_enum_order(kActionNames));

constexpr base::Name<Bias> kBiasNames[] = {
    {Bias::as_is, "as-is"}, {Bias::disable, "disable"}, {Bias::pull_up, "pull-up"}, {Bias::pull_down, "pull-down"}};
static_assert(base::in_enum_order(kBiasNames));

struct ButtonDefault {
  std::string_view name;
  Action action, long_action;
  std::string_view key;
};
constexpr ButtonDefault kButtonDefaults[] = {{"play", Action::pause, Action::restart, "space"},
                                             {"next", Action::next, Action::none, "n"},
                                             {"previous", Action::previous, Action::none, "p"},
                                             {"check", Action::check, Action::none, "c"}};

}  // namespace

std::string_view to_string(Action a) {
  return base::name_of(kActionNames, a);
}
bool parse_action(std::string_view text, Action& out) {
  return base::parse_name(kActionNames, text, out);
}
std::string action_names() {
  return base::names_text(kActionNames);
}

namespace {

// What a value is, for "got ...": the value itself where it is a scalar, else its type.
std::string describe(const toml::node& node) {
  std::ostringstream text;
  if (node.is_string())
    text << "'" << node.as_string()->get() << "'";
  else if (node.is_integer())
    text << node.as_integer()->get();
  else if (node.is_floating_point()) {
    text << node.as_floating_point()->get();
    // 720.0 is not the integer 720: say it is a float.
    if (text.str().find_first_of(".eni") == std::string::npos) text << ".0";
  } else if (node.is_boolean())
    text << (node.as_boolean()->get() ? "true" : "false");
  else
    text << node.type();
  return text.str();
}

std::string position(const std::string& source, const toml::source_region& where) {
  return source + ":" + std::to_string(where.begin.line) + ":" + std::to_string(where.begin.column);
}

// Typed field access whose errors name the file, line and column, the field, what was expected and
// what was there, as playlists and display files do.
class Fields {
 public:
  Fields(const toml::table& t, std::string source, std::string prefix)
      : t_(t), source_(std::move(source)), prefix_(std::move(prefix)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& expected) const {
    const toml::node* n = t_.get(key);
    throw ConfigError(position(source_, n != nullptr ? n->source() : t_.source()) + ": " + prefix_ + key + ": expected " +
                      expected + ", got " + (n != nullptr ? describe(*n) : "nothing"));
  }
  // A key the format does not have is an error, not ignored: a typo would otherwise do nothing.
  void only(std::initializer_list<std::string_view> keys) const {
    for (const auto& [key, node] : t_) {
      if (std::find(keys.begin(), keys.end(), key.str()) != keys.end()) continue;
      std::string list;
      for (std::string_view name : keys) list += (list.empty() ? "" : ", ") + std::string(name);
      throw ConfigError(position(source_, node.source()) + ": " + prefix_ + std::string(key.str()) +
                        ": unknown key (expected one of " + list + ")");
    }
  }
  std::string str(const std::string& key, std::string fallback, bool required = false) const {
    const toml::node* n = t_.get(key);
    if (!n) {
      if (required) fail(key, "a string");
      return fallback;
    }
    if (auto v = n->value<std::string>(); v && n->is_string()) return *v;
    fail(key, "a string");
  }
  long long integer(const std::string& key, long long fallback, long long lo, long long hi) const {
    const toml::node* n = t_.get(key);
    if (!n) return fallback;
    // as_integer, not value<long long>: toml++ converts a float such as 1e280 to an integer
    // without a range check (undefined behaviour, found by tests/fuzz).
    const toml::value<int64_t>* v = n->as_integer();
    if (!v || v->get() < lo || v->get() > hi) fail(key, "an integer in " + std::to_string(lo) + ".." + std::to_string(hi));
    return v->get();
  }
  bool has(const std::string& key) const { return t_.get(key) != nullptr; }
  bool boolean(const std::string& key, bool fallback) const {
    const toml::node* n = t_.get(key);
    if (!n) return fallback;
    if (!n->is_boolean()) fail(key, "true or false");
    return *n->value<bool>();
  }
  // An element of the list `key`, at its own position: "schedule.open[1]: expected ..., got '...'".
  [[noreturn]] void fail_at(const toml::node& element, const std::string& key, std::size_t index,
                            const std::string& expected) const {
    throw ConfigError(position(source_, element.source()) + ": " + prefix_ + key + "[" + std::to_string(index) + "]: expected " +
                      expected + ", got " + describe(element));
  }
  // A list given, each element checked by the caller; `expected` when it is missing or not a list.
  const toml::array& list(const std::string& key, const std::string& expected) const {
    const toml::node* n = t_.get(key);
    if (n == nullptr || !n->is_array() || n->as_array()->empty()) fail(key, expected);
    return *n->as_array();
  }
  const std::string& source() const { return source_; }
  const std::string& prefix() const { return prefix_; }

 private:
  const toml::table& t_;
  std::string source_, prefix_;
};

// One GPIO line serves one button or one LED: the kernel grants a line to one request, so a line
// named twice would fail on the board, or (an LED driving a button's input) misbehave silently.
class LineOwners {
 public:
  void claim(const Fields& f, const GpioLine& line, const std::string& owner) {
    const std::string key = line.line_name.empty() ? line.chip + ":" + std::to_string(line.offset) : "name " + line.line_name;
    const auto [it, fresh] = owners_.emplace(key, owner);
    if (!fresh)
      f.fail(line.line_name.empty() ? "offset" : "line",
             "a GPIO line no other button or LED uses (" + it->second + " uses " + line.describe() + ")");
  }

 private:
  std::map<std::string, std::string> owners_;
};

GpioLine read_line(const Fields& f) {
  GpioLine l;
  l.line_name = f.str("line", "");
  l.chip = f.str("chip", "");
  l.offset = static_cast<int>(f.integer("offset", -1, 0, 1023));
  if (l.line_name.empty() && (l.chip.empty() || l.offset < 0)) f.fail("line", "a line name, or 'chip' and 'offset'");
  l.active_low = f.boolean("active_low", false);
  if (!base::parse_name(kBiasNames, f.str("bias", "as-is"), l.bias)) f.fail("bias", "one of " + base::names_text(kBiasNames));
  return l;
}

ButtonTiming read_timing(const Fields& f, ButtonTiming t) {
  using std::chrono::milliseconds;
  t.debounce = milliseconds(f.integer("debounce_ms", std::chrono::duration_cast<milliseconds>(t.debounce).count(), 0, 1000));
  t.long_press =
      milliseconds(f.integer("long_press_ms", std::chrono::duration_cast<milliseconds>(t.long_press).count(), 0, 60000));
  t.repeat_delay =
      milliseconds(f.integer("repeat_delay_ms", std::chrono::duration_cast<milliseconds>(t.repeat_delay).count(), 0, 60000));
  t.repeat_interval = milliseconds(
      f.integer("repeat_interval_ms", std::chrono::duration_cast<milliseconds>(t.repeat_interval).count(), 10, 60000));
  return t;
}

// "2026-12-24" or a TOML date (2026-12-24); none when it is neither or no such day exists.
std::optional<std::chrono::year_month_day> date_of(const toml::node& node) {
  int year = 0;
  unsigned month = 0, day = 0;
  if (const auto* d = node.as_date()) {
    year = d->get().year;
    month = d->get().month;
    day = d->get().day;
  } else if (const auto* s = node.as_string(); s != nullptr && s->get().size() == 10) {
    const std::string& text = s->get();
    if (text[4] != '-' || text[7] != '-' || std::sscanf(text.c_str(), "%4d-%2u-%2u", &year, &month, &day) != 3)
      return std::nullopt;
  } else {
    return std::nullopt;
  }
  const std::chrono::year_month_day date{std::chrono::year(year), std::chrono::month(month), std::chrono::day(day)};
  return date.ok() ? std::optional(date) : std::nullopt;
}

OpeningHours read_schedule(const Fields& f) {
  f.only({"open", "timezone", "holidays"});
  const toml::array& open = f.list("open", "a list of weekly ranges such as [\"Mo-Fr 09:00-18:00\", \"Sa 10:00-16:00\"]");
  std::vector<OpeningRange> ranges;
  for (std::size_t i = 0; i < open.size(); ++i) {
    const toml::node& element = *open.get(i);
    OpeningRange range;
    std::string expected = "a string such as \"Mo-Fr 09:00-18:00\"";
    if (!element.is_string() || !parse_opening_range(element.as_string()->get(), range, expected))
      f.fail_at(element, "open", i, expected);
    ranges.push_back(range);
  }
  std::vector<std::chrono::year_month_day> holidays;
  if (f.has("holidays")) {
    const toml::array& days = f.list("holidays", "a list of dates (2026-12-24 or \"2026-12-24\")");
    for (std::size_t i = 0; i < days.size(); ++i) {
      const std::optional<std::chrono::year_month_day> day = date_of(*days.get(i));
      if (!day) f.fail_at(*days.get(i), "holidays", i, "a date that exists, as 2026-12-24 or \"2026-12-24\"");
      holidays.push_back(*day);
    }
  }
  std::string error;
  std::optional<OpeningHours> hours = OpeningHours::make(std::move(ranges), f.str("timezone", ""), std::move(holidays), error);
  if (!hours) f.fail("timezone", error);
  return std::move(*hours);
}

std::string resolve(const std::string& source, const std::string& path) {
  if (path.empty() || path[0] == '/') return path;
  const auto slash = source.rfind('/');
  return slash == std::string::npos ? path : source.substr(0, slash + 1) + path;
}

}  // namespace

BoardConfig parse_board(const std::string& toml_text, const std::string& source_name) {
  toml::table root;
  try {
    root = toml::parse(toml_text, source_name);
  } catch (const toml::parse_error& e) {
    std::ostringstream os;
    os << source_name << ":" << e.source().begin.line << ":" << e.source().begin.column << ": " << e.description();
    throw ConfigError(os.str());
  }
  BoardConfig b;
  b.source = source_name;
  const Fields top(root, source_name, "");
  auto table = [&](const char* key) -> const toml::table* {
    const toml::node* n = root.get(key);
    if (n && !n->is_table()) top.fail(key, "a table");
    return n ? n->as_table() : nullptr;
  };
  auto array = [&](const char* key) -> const toml::array* {
    const toml::node* n = root.get(key);
    if (n && !n->is_array_of_tables()) top.fail(key, "an array of tables ([[" + std::string(key) + "]])");
    return n ? n->as_array() : nullptr;
  };

  top.only({"board", "display", "schedule", "buttons", "button", "led", "camera", "mock"});
  if (const auto* t = table("board")) {
    const Fields f(*t, source_name, "board.");
    f.only({"name", "consumer", "status_file", "control", "metrics_file", "self_check_interval_s"});
    b.name = f.str("name", "");
    b.consumer = f.str("consumer", b.consumer);
    b.status_file = f.str("status_file", "");
    b.control = f.str("control", "");
    b.metrics_file = f.str("metrics_file", "");
    b.self_check_interval_s = static_cast<double>(f.integer("self_check_interval_s", 0, 0, 86400 * 7));
  }
  if (const auto* t = table("display")) {
    const Fields f(*t, source_name, "display.");
    f.only({"rotation"});
    b.display_rotation = static_cast<int>(f.integer("rotation", 0, 0, 270));
    if (b.display_rotation % 90 != 0) f.fail("rotation", "0, 90, 180 or 270 (degrees clockwise)");
  }
  if (const auto* t = table("schedule")) b.schedule = read_schedule(Fields(*t, source_name, "schedule."));
  LineOwners owners;
  ButtonTiming defaults;
  if (const auto* t = table("buttons")) {
    const Fields f(*t, source_name, "buttons.");
    f.only({"debounce_ms", "long_press_ms", "repeat_delay_ms", "repeat_interval_ms"});
    defaults = read_timing(f, defaults);
  }
  if (const auto* a = array("button")) {
    for (std::size_t i = 0; i < a->size(); ++i) {
      const Fields f(*a->get(i)->as_table(), source_name, "button[" + std::to_string(i) + "].");
      f.only({"name", "line", "chip", "offset", "active_low", "bias", "debounce_ms", "long_press_ms", "repeat_delay_ms",
              "repeat_interval_ms", "action", "long_press_action", "key"});
      ButtonConfig c;
      c.name = f.str("name", "", true);
      c.line = read_line(f);
      owners.claim(f, c.line, "button '" + c.name + "'");
      c.timing = read_timing(f, defaults);
      for (const ButtonDefault& d : kButtonDefaults)
        if (d.name == c.name) {
          c.action = d.action;
          c.long_action = d.long_action;
          c.key = d.key;
        }
      if (!parse_action(f.str("action", std::string(to_string(c.action))), c.action))
        f.fail("action", "one of " + action_names());
      if (!parse_action(f.str("long_press_action", std::string(to_string(c.long_action))), c.long_action))
        f.fail("long_press_action", "one of " + action_names());
      c.key = f.str("key", c.key);
      b.buttons.push_back(std::move(c));
    }
  }
  if (b.buttons.size() > 255) top.fail("button", "at most 255 buttons");
  if (const auto* a = array("led")) {
    for (std::size_t i = 0; i < a->size(); ++i) {
      const Fields f(*a->get(i)->as_table(), source_name, "led[" + std::to_string(i) + "].");
      f.only({"name", "line", "chip", "offset", "active_low", "bias"});
      LedConfig c;
      c.name = f.str("name", "", true);
      c.line = read_line(f);
      owners.claim(f, c.line, "LED '" + c.name + "'");
      b.leds.push_back(std::move(c));
    }
  }
  if (const auto* t = table("camera")) {
    const Fields f(*t, source_name, "camera.");
    f.only({"device", "width", "height", "format", "buffers", "reopen_interval_ms", "frame_timeout_ms"});
    CameraConfig c;
    c.device = f.str("device", "", true);
    c.width = static_cast<int>(f.integer("width", c.width, 16, 8192));
    c.height = static_cast<int>(f.integer("height", c.height, 16, 8192));
    if (!parse_pixel_format(f.str("format", "auto"), c.format)) f.fail("format", "one of " + pixel_format_names());
    c.buffers = static_cast<int>(f.integer("buffers", c.buffers, 2, 32));
    c.reopen_interval = std::chrono::milliseconds(f.integer("reopen_interval_ms", c.reopen_interval.count(), 100, 600000));
    c.frame_timeout = std::chrono::milliseconds(f.integer("frame_timeout_ms", c.frame_timeout.count(), 100, 600000));
    b.camera = c;
  }
  if (const auto* t = table("mock")) {
    const Fields f(*t, source_name, "mock.");
    f.only({"button_script", "camera_images"});
    b.mock_button_script = resolve(source_name, f.str("button_script", ""));
    if (const toml::node* n = t->get("camera_images")) {
      const toml::array* imgs = n->as_array();
      if (!imgs) f.fail("camera_images", "an array of image paths");
      for (const auto& v : *imgs) {
        if (!v.is_string()) f.fail("camera_images", "an array of strings");
        b.mock_camera_images.push_back(resolve(source_name, *v.value<std::string>()));
      }
    }
  }
  return b;
}

// Used when no board file is given: what a Pi with three buttons and two LEDs would have.
constexpr const char* kBuiltinBoardText = R"(
[board]
name = "built-in mock board"
self_check_interval_s = 0
[buttons]
debounce_ms = 20
long_press_ms = 600
[[button]]
name = "play"
line = "GPIO17"
[[button]]
name = "next"
line = "GPIO27"
repeat_delay_ms = 400
repeat_interval_ms = 100
[[button]]
name = "check"
line = "GPIO22"
[[led]]
name = "status"
line = "GPIO23"
[[led]]
name = "error"
line = "GPIO24"
[camera]
device = "/dev/v4l/by-id/mock-camera"
)";

BoardConfig builtin_mock_board() {
  return parse_board(kBuiltinBoardText, "<built-in board>");
}

BoardConfig load_board(const std::string& path) {
  std::string text, error;
  if (!base::read_regular_file(path, "board file", kMaxBoardFileBytes, text, error)) throw ConfigError(error);
  return parse_board(text, path);
}

}  // namespace hal
