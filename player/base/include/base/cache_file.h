#pragma once
// Files the player keeps between runs to start faster (linked programs, prepared lighting
// environments): named by one hash of what they were made from, checked by a second, unrelated one
// and a checksum, written whole or not at all, and pruned least recently used first. A cache file is
// only ever a shortcut: whatever is wrong with it, the caller makes the thing again.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

namespace base {

// Two unrelated 64-bit hashes: a file is found by one (fnv1a, also the payload's checksum) and
// checked by the other (word_hash), so a collision of one is not enough to read the wrong file.
inline constexpr std::uint64_t kFnvOffset = 0xcbf29ce484222325ull;
std::uint64_t fnv1a(std::uint64_t hash, const void* data, std::size_t size);
std::uint64_t word_hash(std::uint64_t hash, std::string_view bytes);

// A cache file's bytes: an 8-character magic naming the kind and version, `key_check` (the second
// hash of what the payload was made from), the payload's length and checksum, then the payload.
std::string seal_cache_payload(std::string_view magic, std::uint64_t key_check, std::string_view payload);
// The payload of such a file when its magic, key check, length and checksum all hold; nothing when
// any does not (a damaged, truncated or foreign file).
std::optional<std::string_view> unseal_cache_payload(std::string_view file, std::string_view magic, std::uint64_t key_check);

// "0123456789abcdef" + suffix: the file name for a key.
std::string cache_file_name(std::uint64_t key, std::string_view suffix);

// Writes `bytes` to a file beside `path` and renames it over `path`: a reader (another player
// starting) sees the old file or the whole new one. False with why in `error`; nothing is left
// behind when it fails.
bool write_file_whole(const std::filesystem::path& path, std::string_view bytes, std::string& error);

// All of `path` into `out`, and its modification time renewed: load order is what
// prune_least_recent() keeps. False when there is no such file (or it cannot be opened).
bool read_cache_file(const std::filesystem::path& path, std::string& out);

// Removes the least recently written or read files of `dir` until at most max_files of them and
// max_bytes in all remain. Every regular file counts, so leftovers of a write cut short are bounded too.
void prune_least_recent(const std::filesystem::path& dir, std::size_t max_files, std::uintmax_t max_bytes);

// The running executable's GNU build id (hex), or "" when it was linked without one: whatever this
// build computed, another build may compute differently, so files it keeps carry it in their key.
const std::string& executable_build_id();

}  // namespace base
