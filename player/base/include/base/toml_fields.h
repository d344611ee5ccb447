#pragma once
// Typed access to one TOML table whose errors name the file, line and column, the key, what was
// expected and what was there ("fleet.toml:3:13: status_period_s: expected seconds in 0.2..3600,
// got 'five'"), and refuse keys the format does not have: a typo must not silently do nothing.
// In a library of its own (player_base_toml) so that only its users build against toml++.
#include <toml++/toml.h>

#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>

namespace base {

class TomlError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A node's value for "got ...": strings quoted, numbers as written back, other types by name.
std::string describe_toml(const toml::node& node);

class TomlFields {
 public:
  TomlFields(const toml::table& table, std::string source, std::string prefix = {})
      : table_(table), source_(std::move(source)), prefix_(std::move(prefix)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& expected) const;
  // Every key of the table is one of `keys`.
  void only(std::initializer_list<std::string_view> keys) const;
  bool has(const std::string& key) const { return table_.get(key) != nullptr; }

  // Each returns `fallback` when the key is absent.
  std::string string(const std::string& key, std::string fallback) const;
  bool boolean(const std::string& key, bool fallback) const;
  // An integer or a float in [low, high]; `what` says what it is ("seconds").
  double number(const std::string& key, double fallback, double low, double high, const std::string& what) const;

 private:
  const toml::table& table_;
  std::string source_, prefix_;
};

// `text` as TOML, the table given to `read` (which throws TomlError); a syntax error names the
// file, line and column too. False and the message.
template <typename Read>
bool read_toml(std::string_view text, const std::string& source, Read&& read, std::string& error) {
  try {
    const toml::table table = toml::parse(text, source);
    read(table);
    return true;
  } catch (const toml::parse_error& e) {
    error = source + ":" + std::to_string(e.source().begin.line) + ":" + std::to_string(e.source().begin.column) + ": " +
            std::string(e.description());
  } catch (const TomlError& e) {
    error = e.what();
  }
  return false;
}

}  // namespace base
