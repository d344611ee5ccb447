#include "base/errno_text.h"
#include "base/read_file.h"
#include "content/content.h"
#include "lightfield/display_file.h"
#include "playback/playlist.h"
#include "render/settings.h"
#include "scene/load.h"
#include "store.h"
#include "unpack.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <ctime>
#include <ostream>
#include <set>

namespace content {
namespace fs = std::filesystem;
namespace {

std::string counted(std::size_t n, const char* what) {
  return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
}

bool tar_name(const std::string& path) {
  for (const char* end : {".tar", ".tar.gz", ".tgz", ".tar.xz", ".txz", ".tar.zst", ".tar.bz2"}) {
    const std::string_view suffix(end);
    if (path.size() > suffix.size() && path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0) return true;
  }
  return false;
}

// A tar made of a folder (`tar -cf show.tar show/`) holds the bundle one level down.
fs::path bundle_folder(const fs::path& unpacked) {
  if (fs::exists(unpacked / kPlaylistName)) return unpacked;
  std::error_code ec;
  std::vector<fs::path> entries;
  for (const fs::directory_entry& entry : fs::directory_iterator(unpacked, ec)) entries.push_back(entry.path());
  if (entries.size() == 1 && fs::is_directory(entries.front()) && fs::exists(entries.front() / kPlaylistName))
    return entries.front();
  return unpacked;
}

// Installed files are read-only, and synced before the swap: a power cut after it finds them whole.
bool seal(const fs::path& folder, std::string& error) {
  std::error_code ec;
  std::vector<fs::path> folders{folder};
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(folder, ec)) {
    if (entry.is_directory(ec)) {
      folders.push_back(entry.path());
      continue;
    }
    const int fd = open(entry.path().c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0 || fsync(fd) != 0 || fchmod(fd, 0444) != 0) {
      error = entry.path().string() + ": cannot sync it (" + base::errno_text(errno) + ")";
      if (fd >= 0) close(fd);
      return false;
    }
    close(fd);
  }
  for (auto it = folders.rbegin(); it != folders.rend(); ++it) chmod(it->c_str(), 0555);
  return !ec;
}

std::string new_id(std::uint64_t hash) {
  char text[64];
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  const std::size_t n = std::strftime(text, sizeof text, "%Y%m%dT%H%M%SZ", &utc);
  std::snprintf(text + n, sizeof text - n, "-%012" PRIx64, hash >> 16);
  return text;
}

void remove_tree(const fs::path& folder) {
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(folder, ec))
    if (entry.is_directory(ec)) fs::permissions(entry.path(), fs::perms::owner_all, fs::perm_options::add, ec);
  fs::permissions(folder, fs::perms::owner_all, fs::perm_options::add, ec);
  fs::remove_all(folder, ec);
}

}  // namespace

bool check_bundle(const std::string& folder, std::ostream& log, std::string& checked, std::string& error) {
  const std::string playlist_path = (fs::path(folder) / kPlaylistName).string();
  playback::ParseOptions options;
  options.content_root = folder;
  options.validate_setting = render::validate_setting;
  playback::Playlist playlist;
  if (!playback::load_playlist(playlist_path, options, playlist, error)) return false;
  std::set<std::string> scenes, displays, environments;
  for (const playback::Item& item : playlist.items) {
    if (item.scene.rfind("builtin:", 0) != 0) scenes.insert(item.scene);
    if (!item.display.empty()) displays.insert(item.display);
    if (!item.environment.empty() && item.environment.rfind("builtin:", 0) != 0) environments.insert(item.environment);
  }
  for (const std::string& spec : scenes) {
    scene::Scene scene;
    if (!scene::load(spec, scene, error, log)) return false;
  }
  for (const std::string& path : displays) {
    lightfield::Display display;
    if (!lightfield::load_display(path, display, error)) return false;
  }
  for (const std::string& spec : environments) {
    std::shared_ptr<const scene::Environment> environment;
    if (!scene::load_environment_spec(spec, environment, error)) return false;
  }
  checked = "the playlist (" + counted(playlist.items.size(), "item") + "), " + counted(scenes.size(), "scene") +
            (displays.empty() ? "" : ", " + counted(displays.size(), "display file")) +
            (environments.empty() ? "" : ", " + counted(environments.size(), "environment"));
  return true;
}

bool install(const InstallOptions& options, std::ostream& out, std::string& id, std::string& error) {
  const std::string& root = options.root;
  std::error_code ec;
  fs::create_directories(store::versions_dir(root), ec);
  if (ec) {
    error = root + ": cannot make the content root (" + ec.message() + ")";
    return false;
  }
  const int lock = store::lock_root(root, error);
  if (lock < 0) return false;
  const auto fail = [&](const std::string& why) {
    error = why;
    store::record(root, false, options.source, "", why);
    close(lock);
    return false;
  };
  const fs::file_status source = fs::status(options.source, ec);
  const bool is_tar = fs::is_regular_file(source) && tar_name(options.source);
  if (!fs::is_directory(source) && !is_tar)
    return fail(options.source + ": expected a folder or a .tar (.tar.gz, .tar.xz, .tar.zst) of one" +
                (fs::exists(source) ? "" : " (there is nothing there)"));

  // Beside the versions, on the same file system, so that making it a version is a rename.
  std::string incoming = (store::versions_dir(root) / ".incoming-XXXXXX").string();
  if (mkdtemp(incoming.data()) == nullptr) return fail(incoming + ": cannot make it (" + base::errno_text(errno) + ")");
  out << (is_tar ? "unpacking " : "copying ") << options.source << "\n";
  Unpacked unpacked;
  const bool brought = is_tar ? unpack_tar(options.source, incoming, options.max_bytes, unpacked, error)
                              : copy_folder(options.source, incoming, options.max_bytes, unpacked, error);
  const auto refuse = [&](const std::string& why) {
    remove_tree(incoming);
    return fail(why);
  };
  if (!brought) return refuse(error);
  const fs::path bundle = bundle_folder(incoming);
  if (!fs::exists(bundle / kPlaylistName))
    return refuse(options.source + ": no " + std::string(kPlaylistName) + " at the top of the bundle (nor in its one folder)");
  out << "checking " << counted(unpacked.files, "file") << " (" << base::byte_size_text(unpacked.bytes)
      << ") with the player's loader\n";
  std::string checked;
  if (!check_bundle(bundle.string(), out, checked, error)) {
    // The copy's path in messages is the source's, which the person installing knows.
    std::string why = error;
    for (std::size_t at = why.find(bundle.string()); at != std::string::npos; at = why.find(bundle.string(), at))
      why.replace(at, bundle.string().size(), options.source);
    return refuse(why + " (the bundle was not installed; " +
                  (store::current_id(root).empty() ? std::string("nothing plays from it yet")
                                                   : "version " + store::current_id(root) + " stays") +
                  ")");
  }
  out << "ok: " << checked << "\n";

  std::uint64_t bundle_hash = 0;
  if (!hash_folder(bundle.string(), bundle_hash, error)) return refuse(error);
  const std::string hash = new_id(bundle_hash).substr(17);
  for (const std::string& existing : store::version_ids(root))
    if (store::hash_of(existing) == hash) {
      remove_tree(incoming);
      id = existing;
      if (existing == store::current_id(root)) {
        out << "ok: " << options.source << " is version " << existing << ", already current: nothing changed\n";
      } else {
        if (!store::point_current(root, existing, error)) return fail(error);
        out << "ok: " << options.source << " is version " << existing << " again: current -> versions/" << existing << "\n";
      }
      store::record(root, true, options.source, existing, "");
      close(lock);
      return true;
    }

  id = new_id(bundle_hash);
  const fs::path version = store::versions_dir(root) / id;
  if (!seal(bundle, error)) return refuse(error);
  if (rename(bundle.c_str(), version.c_str()) != 0)
    return refuse(version.string() + ": cannot move the bundle into place (" + base::errno_text(errno) + ")");
  if (bundle != fs::path(incoming)) remove_tree(incoming);
  const std::string previous = store::current_id(root);
  if (!store::point_current(root, id, error)) return fail(error);
  out << "ok: installed " << id << " (" << counted(unpacked.files, "file") << ", " << base::byte_size_text(unpacked.bytes)
      << "); current -> versions/" << id << (previous.empty() ? "" : ", was " + previous) << "\n";
  store::record(root, true, options.source, id, "");
  store::prune(root, options.keep, out);
  close(lock);
  return true;
}

bool rollback(const std::string& root, std::ostream& out, std::string& error) {
  const int lock = store::lock_root(root, error);
  if (lock < 0) return false;
  const std::string current = store::current_id(root);
  const std::vector<std::string> ids = store::version_ids(root);
  std::string before;
  for (const std::string& id : ids)
    if (id < current) before = id;
  bool ok = false;
  if (current.empty())
    error = root + ": nothing is installed (no current version)";
  else if (before.empty())
    error = root + ": no version older than the current " + current + " is kept";
  else
    ok = store::point_current(root, before, error);
  if (ok) out << "ok: current -> versions/" << before << ", was " << current << "\n";
  close(lock);
  return ok;
}

bool waiting_bundles(const std::string& inbox, std::vector<std::string>& bundles, std::string& error) {
  std::error_code ec;
  std::vector<std::pair<fs::file_time_type, std::string>> found;
  for (const fs::directory_entry& entry : fs::directory_iterator(inbox, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.front() != '.' && entry.is_regular_file(ec) && tar_name(name))
      found.emplace_back(entry.last_write_time(ec), entry.path().string());
  }
  if (ec) {
    error = inbox + ": cannot read the inbox (" + ec.message() + ")";
    return false;
  }
  std::sort(found.begin(), found.end());
  bundles.clear();
  for (auto& [time, path] : found) bundles.push_back(std::move(path));
  return true;
}

bool list(const std::string& root, std::vector<Version>& versions, std::string& error) {
  std::error_code ec;
  if (!fs::is_directory(store::versions_dir(root), ec)) {
    error = root + ": not a content root (no versions/ folder; `player content install` makes one)";
    return false;
  }
  const std::string current = store::current_id(root);
  versions.clear();
  for (const std::string& id : store::version_ids(root)) {
    Version v{id, id == current, 0, 0};
    for (const fs::directory_entry& entry : fs::recursive_directory_iterator(store::versions_dir(root) / id, ec))
      if (entry.is_regular_file(ec)) {
        v.bytes += entry.file_size(ec);
        ++v.files;
      }
    versions.push_back(v);
  }
  return true;
}

}  // namespace content
