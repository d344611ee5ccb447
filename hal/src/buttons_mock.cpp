#include <limits>
#include <sstream>

#include "base/parse.h"
#include "button_logic.h"
#include "fd.h"
#include "hal/board.h"
#include "hal/mock.h"

namespace hal {

namespace {
// Steps are kept in Nanos and added to the clock's start, so a time must stay far from Nanos' limit
// (292 years); a century is past any test and any kiosk's uptime.
constexpr long long kMaxScriptMs = 100LL * 365 * 24 * 3600 * 1000;
}  // namespace

std::vector<ScriptStep> parse_button_script(const std::string& text, const std::string& source_name) {
  std::vector<ScriptStep> steps;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  long long last_ms = 0;
  while (std::getline(in, line)) {
    ++number;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream fields(line);
    std::string ms_text, name, action;
    if (!(fields >> ms_text)) continue;  // blank or comment
    const std::string where = source_name + ":" + std::to_string(number) + ": ";
    long long ms = 0;
    if (!base::parse_int(ms_text, 0, std::numeric_limits<long long>::max(), ms))
      throw ConfigError(where + "time: expected non-negative milliseconds, got '" + ms_text + "'");
    if (ms > kMaxScriptMs)
      throw ConfigError(where + "time: expected at most " + std::to_string(kMaxScriptMs) + " milliseconds (100 years), got " +
                        ms_text);
    if (ms < last_ms)
      throw ConfigError(where + "time: expected times that do not decrease, got " + ms_text + " after " +
                        std::to_string(last_ms));
    if (!(fields >> name)) throw ConfigError(where + "button: expected a button name after the time");
    if (!(fields >> action) || (action != "press" && action != "release"))
      throw ConfigError(where + "action: expected 'press' or 'release', got '" + action + "'");
    if (std::string extra; fields >> extra) throw ConfigError(where + "expected 3 fields, got more: '" + extra + "'");
    last_ms = ms;
    steps.push_back({std::chrono::milliseconds(ms), name, action == "press"});
  }
  return steps;
}

struct MockButtons::Impl {
  struct Step {
    Nanos at;
    std::size_t button;
    bool pressed;
  };
  std::vector<std::string> names;
  std::vector<Step> script;
  std::size_t next_step = 0;
  detail::ButtonLogic logic;
  const Clock& clock;
  Nanos start;
  base::UniqueFd timer = detail::make_timer();

  Impl(std::vector<MockButtonSpec> buttons, std::vector<ScriptStep> steps, const Clock& c)
      : logic(timings(buttons)), clock(c), start(c.now()) {
    for (auto& b : buttons) names.push_back(std::move(b.name));
    for (const auto& s : steps) {
      std::size_t i = 0;
      while (i < names.size() && names[i] != s.button) ++i;
      if (i == names.size()) throw ConfigError("button script: button '" + s.button + "': expected one of the board's buttons");
      script.push_back({start + s.at, i, s.pressed});
    }
    rearm();
  }
  static std::vector<ButtonTiming> timings(const std::vector<MockButtonSpec>& buttons) {
    std::vector<ButtonTiming> t;
    for (const auto& b : buttons) t.push_back(b.timing);
    return t;
  }
  void rearm() {
    Nanos next = logic.next_deadline();
    if (next_step < script.size()) next = std::min(next, script[next_step].at);
    detail::arm_timer(timer.get(), next);
  }
};

MockButtons::MockButtons(std::vector<MockButtonSpec> buttons, std::vector<ScriptStep> script, const Clock& clock)
    : impl_(std::make_unique<Impl>(std::move(buttons), std::move(script), clock)) {}
MockButtons::~MockButtons() = default;
int MockButtons::fd() const {
  return impl_->timer.get();
}
std::size_t MockButtons::count() const {
  return impl_->names.size();
}
std::string_view MockButtons::name(std::size_t button) const {
  return impl_->names[button];
}

std::size_t MockButtons::dropped() const {
  return impl_->logic.dropped();
}

const std::string& MockButtons::last_error() const {
  static const std::string none;
  return none;
}

void MockButtons::inject(std::size_t button, bool pressed) {
  impl_->logic.edge(button, pressed, impl_->clock.now());
  detail::arm_timer(impl_->timer.get(), Nanos(1));  // wake the poll loop now
}

std::size_t MockButtons::read(std::span<ButtonEvent> out) {
  Impl& m = *impl_;
  detail::drain(m.timer.get());
  const Nanos now = m.clock.now();
  while (m.next_step < m.script.size() && m.script[m.next_step].at <= now) {
    const auto& s = m.script[m.next_step++];
    m.logic.edge(s.button, s.pressed, s.at);
  }
  m.logic.advance(now);
  m.rearm();
  return m.logic.drain(out);
}

}  // namespace hal
