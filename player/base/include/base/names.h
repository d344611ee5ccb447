#pragma once
// One table per enum, mapping each value to the name users write (board files, options, logs).
// name(), parsing and the "one of ..." lists of errors and --help all read the same table, so a
// name is written once. Tables are listed in the enum's order; `in_enum_order` lets the defining
// file static_assert it, so a value added to the enum without a name fails to compile there.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace base {

template <class E>
struct Name {
  E value;
  std::string_view name;
};

// True when entry i names the enum value i: a table that skips or reorders a value is refused.
template <class E, std::size_t N>
constexpr bool in_enum_order(const Name<E> (&table)[N]) {
  for (std::size_t i = 0; i < N; ++i)
    if (static_cast<std::size_t>(table[i].value) != i) return false;
  return true;
}

// "?" for a value the table lacks (a value cast from a number read elsewhere).
template <class E, std::size_t N>
constexpr std::string_view name_of(const Name<E> (&table)[N], E value) {
  for (const Name<E>& entry : table)
    if (entry.value == value) return entry.name;
  return "?";
}

// False (and `out` untouched) when `text` is no name in the table; names are matched exactly.
template <class E, std::size_t N>
constexpr bool parse_name(const Name<E> (&table)[N], std::string_view text, E& out) {
  for (const Name<E>& entry : table)
    if (entry.name == text) {
      out = entry.value;
      return true;
    }
  return false;
}

// Every name in the table's order, for CLI11's IsMember and for tests.
template <class E, std::size_t N>
std::vector<std::string> names_of(const Name<E> (&table)[N]) {
  std::vector<std::string> names;
  for (const Name<E>& entry : table) names.emplace_back(entry.name);
  return names;
}

// "a, b, c", or with `last` " or ": "a, b or c"; for errors ("expected one of ...") and --help.
std::string join_names(const std::vector<std::string>& names, std::string_view last = ", ");

template <class E, std::size_t N>
std::string names_text(const Name<E> (&table)[N], std::string_view last = ", ") {
  return join_names(names_of(table), last);
}

}  // namespace base
