#pragma once
// The concrete platforms; only the registry in platform.cpp names them.
#include "platform/platform.h"

namespace platform {
std::unique_ptr<Platform> create_egl(const Options& options, std::string& error);
std::unique_ptr<Platform> create_osmesa(const Options& options, std::string& error);
std::unique_ptr<Platform> create_window(const Options& options, std::string& error);
std::unique_ptr<Platform> create_kms(const Options& options, std::string& error);
// The first DRM node with KMS resources (connectors and CRTCs), for choose_auto; false when none.
bool find_kms_device(std::string& path);
}  // namespace platform
