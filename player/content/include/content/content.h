#pragma once
// Content that arrives whole: a content root holds versions/ID/ (each an installed bundle, a
// playlist.toml and the files it names, read-only once installed) and `current`, a symlink to one of
// them, swapped atomically (a new link renamed over it). `player content install` checks a bundle
// with the player's own loader before the swap, so a half-copied or broken bundle never reaches a
// screen; `player content rollback` swaps back. The player plays ROOT/current/playlist.toml and
// follows a swap at its next item boundary (app's BundleFollower). docs/content.md.
#include <cstdint>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

namespace content {

inline constexpr std::string_view kDefaultRoot = "/var/lib/ssao-player/content";
inline constexpr std::string_view kPlaylistName = "playlist.toml";
inline constexpr std::string_view kCurrentName = "current";
inline constexpr std::string_view kVersionsName = "versions";
// The last install's outcome, for the player to report a refused bundle on its channels.
inline constexpr std::string_view kRecordName = "last-install.json";

struct InstallOptions {
  std::string root = std::string(kDefaultRoot);
  std::string source;                    // a folder, or a .tar (optionally .gz, .xz, .zst) of one
  int keep = 3;                          // previous versions kept besides the current one
  std::uint64_t max_bytes = 4ull << 30;  // the bundle's size budget, unpacked
};

struct Version {
  std::string id;  // YYYYMMDDTHHMMSSZ-HASH: sorts by install time
  bool current = false;
  std::uint64_t bytes = 0;
  std::size_t files = 0;
};

// Copies or unpacks the bundle beside the versions, checks the playlist and every file it names
// with the player's loader, and only then makes it current. Prints progress to `out`. False and
// why (the bundle's file, the field, what was expected), with nothing changed but the record.
// An install of the bundle already current changes nothing and says so.
bool install(const InstallOptions& options, std::ostream& out, std::string& id, std::string& error);
// `current` back to the version installed before it. False and why (no earlier version).
bool rollback(const std::string& root, std::ostream& out, std::string& error);
// The bundles (.tar, .tar.gz, .tgz, .tar.xz, .tar.zst, .tar.bz2) in `inbox`, oldest first; names
// starting with '.' (a transfer in progress) are not taken.
bool waiting_bundles(const std::string& inbox, std::vector<std::string>& bundles, std::string& error);
// Every version, oldest first.
bool list(const std::string& root, std::vector<Version>& versions, std::string& error);

// The bundle in `folder` as the player would play it: the playlist parses, and every scene, display
// and environment it names loads. False and the first problem; `checked` says what was looked at.
bool check_bundle(const std::string& folder, std::ostream& log, std::string& checked, std::string& error);

}  // namespace content
