#pragma once
#include <cstddef>
#include <string>

namespace fleet {

// The PNG at `png_path` as a JPEG of at most `max_bytes`: halved in size until it fits (a
// dashboard's thumbnail, not an archive). False and why.
bool jpeg_within(const std::string& png_path, std::size_t max_bytes, std::string& jpeg, int& width, int& height,
                 std::string& error);

}  // namespace fleet
