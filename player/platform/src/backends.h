#pragma once
// The concrete platforms; only the registry in platform.cpp names them.
#include "platform/platform.h"

namespace platform {
std::unique_ptr<Platform> create_egl(const Options& options, std::string& error);
std::unique_ptr<Platform> create_osmesa(const Options& options, std::string& error);
std::unique_ptr<Platform> create_window(const Options& options, std::string& error);
}  // namespace platform
