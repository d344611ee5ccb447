#pragma once
// The playlist's scenes on their way to the GPU and there: which the timeline wants (the item shown
// and the next), the loader thread's results, uploads in slices within a budget per frame, and the
// swap of a reloaded scene once its new version is whole, so a reload never shows half a scene.
#include "gl/caps.h"
#include "lightfield/display_file.h"
#include "loader.h"
#include "playback/timeline.h"
#include "render/scene_gpu.h"
#include "scene/animation.h"
#include "scene/scene.h"

#include <cstdint>
#include <iosfwd>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace app {

class StatusReporter;

// A scene on its way to the GPU or there.
struct CachedScene {
  std::unique_ptr<render::SceneGpu> gpu;  // what draws
  scene::Bounds bounds;
  // A new version uploading in slices; it replaces `gpu` once whole.
  std::unique_ptr<render::SceneGpu> incoming;
  scene::Bounds incoming_bounds;
  std::vector<scene::FileCamera> cameras, incoming_cameras;  // the scene's own, for motion = "file"
  // The light field display the item is shown on (null: the platform's own 2D surface).
  std::shared_ptr<const lightfield::Display> display, incoming_display;
  std::string error;                  // failed to load: the item is skipped
  std::vector<std::string> warnings;  // loaded anyway (a texture drawn white): in the status while it plays
  bool requested = false;
  std::unique_ptr<scene::Pose> pose;  // the animated scene's nodes (null: nothing moves)
};

class SceneCache {
 public:
  // Errors go to `status`; the loader's warnings to `err` as they come (they stay in the status too).
  SceneCache(Loader& loader, const gl::Caps& caps, StatusReporter& status, std::ostream& err);

  // A playlist's items: the loader's key of every item, made once per playlist, so the frame loop
  // looks scenes up without building strings. Scenes no item names any more are dropped with their
  // GPU data; items of scenes known to have failed are marked unplayable on `timeline`.
  void set_playlist(const playback::Playlist& playlist, playback::Timeline* timeline);
  const std::string& key_of(int item) const { return keys_[static_cast<size_t>(item)]; }

  // Loads what the cue shows and what follows it, once each.
  void request(const playback::Cue& cue);
  // A scene result of the loader: a failure skips the items of a scene never loaded (a reload that
  // fails keeps the old content); a success makes its items playable and starts its upload.
  void take(Loader::Result& result, playback::Timeline& timeline);
  // One frame's upload budget. True when the scene keyed `shown` was swapped for a new version (its
  // radius may differ: the frame is configured again).
  bool step_uploads(const std::string& shown);

  // The item's scene when it can be drawn (on the GPU, whole), else null.
  const CachedScene* ready(int item) const;
  // Whether a reproducible run can draw the item: its scene failed, or is drawable with no newer
  // version on its way.
  bool settled(int item) const;

  // Poses the item's scene at `item_time` seconds into the item, as its animation keys say
  // (resolved against the scene once, a key it lacks reported and the rest pose shown). Allocates
  // nothing once resolved.
  void pose(int item, double item_time);

  // SIGHUP: every scene again. A changed file: the scenes whose scene or display it is.
  void reload_all();
  void reload(const std::string& path);

  // Scenes replaced by a newer version of their file (the --log line's swaps).
  std::uint64_t swaps() const { return swaps_; }
  // The content's warnings, for the status file.
  void append_warnings(std::vector<std::string>& out) const;

 private:
  void set_playable(const std::string& key, bool playable, playback::Timeline& timeline) const;

  Loader& loader_;
  const gl::Caps& caps_;
  StatusReporter& status_;
  std::ostream& err_;
  std::map<std::string, CachedScene> scenes_;
  std::vector<std::string> keys_;  // load_key() of each playlist item
  // Each item's animation key and speed, and the animation it resolved to in its scene's rig.
  static constexpr int kUnresolved = -3;
  std::vector<std::string> animation_specs_;
  std::vector<double> animation_speeds_;
  std::vector<int> selections_;
  std::uint64_t swaps_ = 0;
};

}  // namespace app
