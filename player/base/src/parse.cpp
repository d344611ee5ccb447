#include "base/parse.h"

namespace base {

bool parse_size(std::string_view text, int max, int& width, int& height) {
  const std::size_t x = text.find('x');
  if (x == std::string_view::npos) return false;
  int w = 0, h = 0;
  if (!parse_int(text.substr(0, x), 1, max, w) || !parse_int(text.substr(x + 1), 1, max, h)) return false;
  width = w;
  height = h;
  return true;
}

}  // namespace base
