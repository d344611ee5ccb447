#pragma once
// A playlist in an installed content bundle (ROOT/current/playlist.toml, `player content`): it is
// played from the version the link points to (ROOT/versions/ID/...), whose files never change, and
// when the link is swapped the next version's playlist is loaded off the loop and held until the
// item on screen ends, so content changes at an item boundary, never mid-item. A refused install
// (ROOT/last-install.json) is reported like any content error.
#include "playback/playlist.h"

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace app {

class BundleFollower {
 public:
  // `playlist_path` through a symbolic link to a folder (the bundle's `current`): that version's
  // playlist, the link resolved; any other path as it is.
  static std::string resolve(const std::string& playlist_path);

  // Follows the link among `playlist_path`'s folders, if any (absolute, as given).
  void open(const std::string& playlist_path);
  bool active() const { return !link_.empty(); }
  // The link's folder, to watch for the swap (a rename over the link) and the install record.
  const std::string& folder() const { return folder_; }

  enum class Event : std::uint8_t { none, swapped, record };
  // What a change in the watched folders means to the bundle.
  Event event_of(const std::string& changed_path) const;
  // The link swapped: the playlist to load now, or "" when it still resolves to the one playing.
  std::string swapped();
  // ROOT/last-install.json changed: the refused install's message, or "" (a good install, or
  // nothing new).
  std::string refused_install();

  // The loader's result for `path` is the next version's playlist.
  bool expects(const std::string& path) const { return !expected_.empty() && path == expected_; }
  // The next version's playlist, loaded while the item of `sequence` (Cue::sequence) plays.
  void hold(std::shared_ptr<const playback::Playlist> playlist, std::uint64_t sequence);
  // Not loaded: the version playing stays.
  void drop() { expected_.clear(); }
  // The held playlist once an item after the one it was loaded during has started.
  std::shared_ptr<const playback::Playlist> take_at(std::uint64_t sequence);
  const std::string& playing() const { return playing_; }

 private:
  std::string link_, folder_, inside_;  // ROOT/current, ROOT, and the playlist's path below the link
  std::string playing_;                 // the resolved playlist of the version on screen
  std::string expected_;                // the resolved playlist being loaded
  std::shared_ptr<const playback::Playlist> held_;
  std::uint64_t held_during_ = 0;
  long long record_time_ = -1;  // the install record last read
};

}  // namespace app
