#include "base/errno_text.h"

#include <cstring>

namespace base {

std::string errno_text(int code) {
  char buffer[256];
  // The GNU strerror_r: returns the text, which may or may not be in `buffer`.
  return strerror_r(code, buffer, sizeof buffer);
}

}  // namespace base
