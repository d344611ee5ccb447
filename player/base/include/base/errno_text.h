#pragma once
// The text of an errno value, for messages that say why a system call failed: "No such file or
// directory". Thread-safe, unlike std::strerror.
#include <string>

namespace base {

std::string errno_text(int code);

}  // namespace base
