#include "play/bundle_follower.h"

#include "base/read_file.h"

#include <nlohmann/json.hpp>

#include <filesystem>

namespace app {
namespace fs = std::filesystem;
namespace {

// The nearest of `path`'s folders that is a symbolic link, or "".
fs::path link_among_folders(const fs::path& path) {
  std::error_code ec;
  for (fs::path folder = path.parent_path(); !folder.empty() && folder != folder.root_path(); folder = folder.parent_path())
    if (fs::is_symlink(fs::symlink_status(folder, ec))) return folder;
  return {};
}

constexpr const char* kRecordName = "last-install.json";

}  // namespace

std::string BundleFollower::resolve(const std::string& playlist_path) {
  const fs::path link = link_among_folders(playlist_path);
  if (link.empty()) return playlist_path;
  std::error_code ec;
  const fs::path resolved = fs::canonical(link, ec);
  return ec ? playlist_path : (resolved / fs::path(playlist_path).lexically_relative(link)).string();
}

void BundleFollower::open(const std::string& playlist_path) {
  const fs::path link = link_among_folders(playlist_path);
  if (link.empty()) return;
  link_ = link.string();
  folder_ = link.parent_path().string();
  inside_ = fs::path(playlist_path).lexically_relative(link).string();
  playing_ = resolve(playlist_path);
  // A record older than this start was seen by whoever installed; only later ones are news.
  std::error_code ec;
  const auto written = fs::last_write_time(fs::path(folder_) / kRecordName, ec);
  if (!ec) record_time_ = written.time_since_epoch().count();
}

BundleFollower::Event BundleFollower::event_of(const std::string& changed_path) const {
  if (!active()) return Event::none;
  if (changed_path == link_) return Event::swapped;
  if (changed_path == (fs::path(folder_) / kRecordName).string()) return Event::record;
  return Event::none;
}

std::string BundleFollower::swapped() {
  const std::string next = resolve((fs::path(link_) / inside_).string());
  if (next == playing_ || next == expected_) return {};
  expected_ = next;
  held_.reset();
  return next;
}

std::string BundleFollower::refused_install() {
  const fs::path record = fs::path(folder_) / kRecordName;
  std::error_code ec;
  const long long written = fs::last_write_time(record, ec).time_since_epoch().count();
  if (ec || written == record_time_) return {};
  record_time_ = written;
  std::string text, error;
  if (!base::read_regular_file(record.string(), "install record", 64 * base::kKiB, text, error)) return {};
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || !j.is_object() || j.value("ok", true)) return {};
  return "content install of " + j.value("source", std::string("?")) + " refused: " + j.value("error", std::string("?"));
}

void BundleFollower::hold(std::shared_ptr<const playback::Playlist> playlist, std::uint64_t sequence) {
  held_ = std::move(playlist);
  held_during_ = sequence;
}

std::shared_ptr<const playback::Playlist> BundleFollower::take_at(std::uint64_t sequence) {
  if (!held_ || sequence <= held_during_) return nullptr;
  playing_ = expected_;
  expected_.clear();
  return std::move(held_);
}

}  // namespace app
