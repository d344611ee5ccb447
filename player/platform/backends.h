#pragma once
// The concrete platforms; only platform.cpp chooses among them.
#include "platform/platform.h"

namespace platform {
std::unique_ptr<Platform> create_egl(bool debug, std::string& error);
std::unique_ptr<Platform> create_osmesa(bool debug, std::string& error);
}  // namespace platform
