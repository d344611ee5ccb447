#include "store.h"

#include "base/errno_text.h"
#include "base/unique_fd.h"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <ctime>
#include <fstream>
#include <ostream>

namespace content::store {

fs::path versions_dir(const std::string& root) {
  return fs::path(root) / kVersionsName;
}
fs::path current_link(const std::string& root) {
  return fs::path(root) / kCurrentName;
}

std::string current_id(const std::string& root) {
  std::error_code ec;
  const fs::path target = fs::read_symlink(current_link(root), ec);
  if (ec || target.parent_path().filename() != kVersionsName) return {};
  return target.filename().string();
}

std::vector<std::string> version_ids(const std::string& root) {
  std::vector<std::string> ids;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(versions_dir(root), ec)) {
    const std::string name = entry.path().filename().string();
    if (!name.empty() && name.front() != '.' && entry.is_directory(ec) && !entry.is_symlink(ec)) ids.push_back(name);
  }
  std::sort(ids.begin(), ids.end());
  return ids;
}

namespace {

bool sync_folder(const fs::path& folder, std::string& error) {
  const base::UniqueFd fd(open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (!fd || fsync(fd.get()) != 0) {
    error = folder.string() + ": cannot sync the folder (" + base::errno_text(errno) + ")";
    return false;
  }
  return true;
}

}  // namespace

bool point_current(const std::string& root, const std::string& id, std::string& error) {
  // Relative, so the root can move (a backup restored elsewhere) without breaking the link.
  const fs::path link = current_link(root), next = fs::path(root) / ".current.next";
  unlink(next.c_str());
  const std::string target = std::string(kVersionsName) + "/" + id;
  if (symlink(target.c_str(), next.c_str()) != 0) {
    error = next.string() + ": cannot make the link (" + base::errno_text(errno) + ")";
    return false;
  }
  if (rename(next.c_str(), link.c_str()) != 0) {
    error = link.string() + ": cannot replace the link (" + base::errno_text(errno) + ")";
    unlink(next.c_str());
    return false;
  }
  return sync_folder(root, error);
}

std::string hash_of(const std::string& id) {
  const std::size_t dash = id.rfind('-');
  return dash == std::string::npos ? std::string() : id.substr(dash + 1);
}

void prune(const std::string& root, int keep, std::ostream& out) {
  const std::string current = current_id(root);
  std::vector<std::string> others;
  for (const std::string& id : version_ids(root))
    if (id != current) others.push_back(id);
  const std::size_t kept = static_cast<std::size_t>(std::max(0, keep));
  if (others.size() <= kept) return;
  for (std::size_t i = 0; i + kept < others.size(); ++i) {
    const fs::path folder = versions_dir(root) / others[i];
    std::error_code ec;
    // Installed read-only: writable again for the removal.
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(folder, ec))
      if (entry.is_directory(ec)) fs::permissions(entry.path(), fs::perms::owner_write, fs::perm_options::add, ec);
    fs::permissions(folder, fs::perms::owner_write, fs::perm_options::add, ec);
    fs::remove_all(folder, ec);
    out << (ec ? "warning: cannot remove the old version " + others[i] + " (" + ec.message() + ")"
               : "removed the old version " + others[i])
        << "\n";
  }
}

void record(const std::string& root, bool ok, const std::string& source, const std::string& id, const std::string& error) {
  const nlohmann::json j = {{"ok", ok}, {"source", source}, {"version", id}, {"error", error}, {"time", std::time(nullptr)}};
  const fs::path next = fs::path(root) / ".last-install.next", file = fs::path(root) / kRecordName;
  {
    std::ofstream stream(next);
    stream << j.dump(2) << "\n";
    if (!stream) return;
  }
  if (rename(next.c_str(), file.c_str()) != 0) unlink(next.c_str());
}

int lock_root(const std::string& root, std::string& error) {
  const fs::path path = fs::path(root) / ".lock";
  const int fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) {
    error = path.string() + ": cannot open the lock (" + base::errno_text(errno) + ")";
    return -1;
  }
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    error = root + ": another `player content` is at work here; try again when it is done";
    close(fd);
    return -1;
  }
  return fd;
}

}  // namespace content::store
