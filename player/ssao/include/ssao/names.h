#pragma once
// One name table per enum: the enum's name, its parser, the command line's choices and the
// settings codec all read the same table, so a name is written once.
#include <optional>
#include <span>
#include <string>
#include <string_view>

namespace names {

template <typename Enum>
struct Named {
  Enum value;
  std::string_view name;
};

template <typename Enum>
std::string_view name_of(std::span<const Named<Enum>> table, Enum value) {
  for (const Named<Enum>& entry : table)
    if (entry.value == value) return entry.name;
  return "?";
}

template <typename Enum>
std::optional<Enum> parse(std::span<const Named<Enum>> table, std::string_view text) {
  for (const Named<Enum>& entry : table)
    if (entry.name == text) return entry.value;
  return std::nullopt;
}

// "a|b|c" by default, or "a, b or c" with separator ", " and last " or ".
template <typename Enum>
std::string choices(std::span<const Named<Enum>> table, std::string_view separator = "|", std::string_view last = "|") {
  std::string text;
  for (size_t i = 0; i < table.size(); ++i) {
    if (i > 0) text += i + 1 == table.size() ? last : separator;
    text += table[i].name;
  }
  return text;
}

}  // namespace names
