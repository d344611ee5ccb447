#include "base/names.h"
#include "base/parse.h"
#include "control/control.h"

#include <cstdio>

namespace control {
namespace {

constexpr base::Name<Verb> kVerbs[] = {
    {Verb::next, "next"},       {Verb::previous, "previous"}, {Verb::pause, "pause"},
    {Verb::resume, "resume"},   {Verb::check, "check"},       {Verb::reload, "reload"},
    {Verb::restart, "restart"}, {Verb::item, "item"},         {Verb::screenshot, "screenshot"},
    {Verb::display, "display"},
};
static_assert(base::in_enum_order(kVerbs));

constexpr int kMaxItem = 1'000'000;

// A message as it came, on one line whatever it holds: what the error shows.
std::string shown(std::string_view text) {
  std::string out = "'";
  for (const char c : text.substr(0, 64)) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u >= 0x7f || c == '\'' || c == '\\') {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02x", u);
      out += hex;
    } else {
      out += c;
    }
  }
  return out + (text.size() > 64 ? "'..." : "'");
}

}  // namespace

std::string_view to_string(Verb verb) {
  return base::name_of(kVerbs, verb);
}

std::string verbs_text() {
  std::vector<std::string> names = base::names_of(kVerbs);
  for (std::string& name : names) {
    if (name == "item") name += " N";
    if (name == "display") name += " on|off";
  }
  return base::join_names(names);
}

bool parse_command(std::string_view message, Command& out, std::string& error) {
  if (message.size() > kMaxMessage) {
    error = "a command of " + std::to_string(message.size()) + " bytes, more than " + std::to_string(kMaxMessage);
    return false;
  }
  // One trailing newline is what `echo` and most scripts send.
  if (!message.empty() && message.back() == '\n') message.remove_suffix(1);
  const std::size_t space = message.find(' ');
  const std::string_view verb_text = message.substr(0, space);
  const std::string_view argument = space == std::string_view::npos ? std::string_view() : message.substr(space + 1);
  Command command;
  if (!base::parse_name(kVerbs, verb_text, command.verb)) {
    error = "unknown command " + shown(message) + " (expected one of " + verbs_text() + ")";
    return false;
  }
  if (command.verb == Verb::item) {
    long long item = -1;
    if (!base::parse_int(argument, 0, kMaxItem, item)) {
      error = "item: expected an item number from 0 (as the status file counts), got " + shown(argument);
      return false;
    }
    command.item = static_cast<int>(item);
  } else if (command.verb == Verb::display) {
    if (argument != "on" && argument != "off") {
      error = "display: expected on or off, got " + shown(argument);
      return false;
    }
    command.display_on = argument == "on";
  } else if (space != std::string_view::npos) {
    error = std::string(verb_text) + ": takes no argument, got " + shown(argument);
    return false;
  }
  out = command;
  return true;
}

std::string format_command(const Command& command) {
  std::string text(to_string(command.verb));
  if (command.verb == Verb::item) text += " " + std::to_string(command.item);
  if (command.verb == Verb::display) text = command.display_on ? "display on" : "display off";
  return text;
}

bool reply_ok(std::string_view reply) {
  return reply == "ok" || reply.starts_with("ok: ");
}

}  // namespace control
