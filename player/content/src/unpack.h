#pragma once
// A bundle's files brought into a fresh folder: copied from a folder, or unpacked from a tar.
// Regular files and folders only; names starting with '.' are left out (editors' and Syncthing's
// files, rsync's partial copies), as the player's watch ignores them.
#include <cstdint>
#include <string>

namespace content {

struct Unpacked {
  std::uint64_t bytes = 0;
  std::size_t files = 0;
};

bool copy_folder(const std::string& source, const std::string& target, std::uint64_t max_bytes, Unpacked& unpacked,
                 std::string& error);
bool unpack_tar(const std::string& source, const std::string& target, std::uint64_t max_bytes, Unpacked& unpacked,
                std::string& error);
// FNV-1a over each file's path (relative to `folder`) and bytes, in path order: the same bundle
// gives the same hash from a folder or a tar. False when a file cannot be read.
bool hash_folder(const std::string& folder, std::uint64_t& hash, std::string& error);

}  // namespace content
