#pragma once
// Checked number parsing for command-line options, board and display files and scripts: the whole
// text or nothing. No leading spaces or '+', no trailing text, no locale (std::from_chars), so
// "12abc", " 5" and "1,5" are refused wherever a number is read. Each returns false and leaves
// `out` untouched when the text is not a number in range; the caller names the field in its error.
#include <charconv>
#include <cmath>
#include <concepts>
#include <limits>
#include <string_view>
#include <system_error>
#include <type_traits>

namespace base {

// A decimal (or `radix`) integer in [low, high].
template <std::integral T>
bool parse_int(std::string_view text, std::type_identity_t<T> low, std::type_identity_t<T> high, T& out, int radix = 10) {
  T value{};
  const char* end = text.data() + text.size();
  const auto [stop, ec] = std::from_chars(text.data(), end, value, radix);
  if (text.empty() || ec != std::errc() || stop != end || value < low || value > high) return false;
  out = value;
  return true;
}

// A finite decimal number ("59.94", "1e-3"); "inf" and "nan" are refused. Range checks are the
// caller's, since they are as often open as closed.
template <std::floating_point T>
bool parse_number(std::string_view text, T& out) {
  T value{};
  const char* end = text.data() + text.size();
  const auto [stop, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || stop != end || !std::isfinite(value)) return false;
  out = value;
  return true;
}

// "WxH": two integers, each in [1, max], joined by one 'x' ("1920x1080").
bool parse_size(std::string_view text, int max, int& width, int& height);

}  // namespace base
