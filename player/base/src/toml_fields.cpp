#include "base/toml_fields.h"

#include <charconv>
#include <cmath>
#include <sstream>

namespace base {
namespace {

std::string position(const std::string& source, const toml::source_region& where) {
  return source + ":" + std::to_string(where.begin.line) + ":" + std::to_string(where.begin.column);
}

}  // namespace

std::string describe_toml(const toml::node& node) {
  if (const auto* s = node.as_string()) return "'" + s->get() + "'";
  if (const auto* i = node.as_integer()) return std::to_string(i->get());
  if (const auto* f = node.as_floating_point()) {
    char text[32];
    const std::to_chars_result end = std::to_chars(text, text + sizeof text, f->get());
    return std::string(text, end.ptr);
  }
  if (const auto* b = node.as_boolean()) return b->get() ? "true" : "false";
  std::ostringstream type;
  type << "a " << node.type();
  return type.str();
}

void TomlFields::fail(const std::string& key, const std::string& expected) const {
  const toml::node* node = table_.get(key);
  throw TomlError(position(source_, node != nullptr ? node->source() : table_.source()) + ": " + prefix_ + key + ": expected " +
                  expected + ", got " + (node != nullptr ? describe_toml(*node) : "nothing"));
}

void TomlFields::only(std::initializer_list<std::string_view> keys) const {
  for (const auto& [key, node] : table_) {
    (void)node;
    bool known = false;
    std::string list;
    for (std::string_view name : keys) {
      known = known || key.str() == name;
      list += (list.empty() ? "" : ", ") + std::string(name);
    }
    if (!known)
      throw TomlError(position(source_, key.source()) + ": " + prefix_ + std::string(key.str()) +
                      ": unknown key (expected one of " + list + ")");
  }
}

std::string TomlFields::string(const std::string& key, std::string fallback) const {
  const toml::node* node = table_.get(key);
  if (node == nullptr) return fallback;
  if (!node->is_string()) fail(key, "a string");
  return node->as_string()->get();
}

bool TomlFields::boolean(const std::string& key, bool fallback) const {
  const toml::node* node = table_.get(key);
  if (node == nullptr) return fallback;
  if (!node->is_boolean()) fail(key, "true or false");
  return node->as_boolean()->get();
}

double TomlFields::number(const std::string& key, double fallback, double low, double high, const std::string& what) const {
  const toml::node* node = table_.get(key);
  if (node == nullptr) return fallback;
  double value = NAN;
  if (const auto* i = node->as_integer())
    value = static_cast<double>(i->get());
  else if (const auto* f = node->as_floating_point())
    value = f->get();
  std::ostringstream range;
  range << what << " in " << low << ".." << high;
  if (!(value >= low && value <= high)) fail(key, range.str());
  return value;
}

}  // namespace base
