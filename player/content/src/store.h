#pragma once
// The content root's layout and its atomic steps, shared by install and rollback.
#include "content/content.h"

#include <filesystem>

namespace content::store {

namespace fs = std::filesystem;

fs::path versions_dir(const std::string& root);
fs::path current_link(const std::string& root);
// The version `current` points to ("" when none or it is not a link into versions/).
std::string current_id(const std::string& root);
// The ids under versions/, oldest first (folders whose name starts with '.' are work in progress).
std::vector<std::string> version_ids(const std::string& root);
// `current` -> versions/ID, by a new link renamed over it, then the root's folder synced.
bool point_current(const std::string& root, const std::string& id, std::string& error);
// Versions beyond the current one and the `keep` newest others are removed.
void prune(const std::string& root, int keep, std::ostream& out);
// ROOT/last-install.json, replaced whole.
void record(const std::string& root, bool ok, const std::string& source, const std::string& id, const std::string& error);
// An exclusive lock on ROOT/.lock for the life of the returned descriptor (-1 and why when not).
int lock_root(const std::string& root, std::string& error);
// The hash part of an id ("20261208T101500Z-0123456789ab" -> "0123456789ab").
std::string hash_of(const std::string& id);

}  // namespace content::store
