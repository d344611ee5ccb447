#include "play/scene_cache.h"

#include "play/status_reporter.h"

#include <algorithm>
#include <iterator>
#include <ostream>

#include <unordered_set>

namespace app {

SceneCache::SceneCache(Loader& loader, const gl::Caps& caps, StatusReporter& status, std::ostream& err)
    : loader_(loader), caps_(caps), status_(status), err_(err) {}

void SceneCache::set_playlist(const playback::Playlist& playlist, playback::Timeline* timeline) {
  keys_.clear();
  animation_specs_.clear();
  animation_speeds_.clear();
  for (const playback::Item& item : playlist.items) {
    keys_.push_back(load_key(item));
    animation_specs_.push_back(item.animation);
    animation_speeds_.push_back(item.animation_speed);
  }
  selections_.assign(keys_.size(), kUnresolved);
  const std::unordered_set<std::string> used(keys_.begin(), keys_.end());
  for (auto it = scenes_.begin(); it != scenes_.end();) it = used.count(it->first) > 0 ? std::next(it) : scenes_.erase(it);
  if (timeline == nullptr) return;
  for (size_t i = 0; i < keys_.size(); ++i) {
    auto found = scenes_.find(keys_[i]);
    if (found != scenes_.end() && !found->second.error.empty()) timeline->set_playable(static_cast<int>(i), false);
  }
}

void SceneCache::request(const playback::Cue& cue) {
  for (int item : {cue.item, cue.next_item}) {
    if (item < 0) continue;
    const std::string& key = key_of(item);
    CachedScene& scene = scenes_[key];
    if (!scene.requested) {
      scene.requested = true;
      loader_.load_scene(key);
    }
  }
}

void SceneCache::set_playable(const std::string& key, bool playable, playback::Timeline& timeline) const {
  for (size_t i = 0; i < keys_.size(); ++i)
    if (keys_[i] == key) timeline.set_playable(static_cast<int>(i), playable);
}

void SceneCache::take(Loader::Result& result, playback::Timeline& timeline) {
  auto found = scenes_.find(result.path);
  if (found == scenes_.end()) return;  // no longer in the playlist
  CachedScene& scene = found->second;
  if (!result.error.empty()) {
    status_.report(ErrorKind::content, result.error);
    if (!scene.gpu) {  // never loaded: skip its items; a reload that fails keeps the old content
      scene.error = result.error;
      set_playable(result.path, false, timeline);
    }
    return;
  }
  scene.error.clear();
  status_.scene_loaded(result.seconds);
  scene.warnings = std::move(result.warnings);
  for (const std::string& warning : scene.warnings) err_ << "warning: " << warning << "\n";
  set_playable(result.path, true, timeline);
  scene.incoming_display = result.display;
  scene.incoming = std::make_unique<render::SceneGpu>();
  scene.incoming->begin(result.scene, caps_);
  scene.incoming_bounds = result.scene->bounds;
  scene.incoming_cameras = result.scene->cameras;
}

// A budget per frame keeps an item change or a reload from showing as a hitch.
bool SceneCache::step_uploads(const std::string& shown) {
  constexpr size_t kBudget = 8u << 20;
  size_t left = kBudget;
  bool shown_swapped = false;
  for (auto& [key, scene] : scenes_) {
    if (!scene.incoming || left == 0) continue;
    const size_t before = scene.incoming->bytes();
    const bool done = scene.incoming->step(left);
    left -= std::min(left, std::max<size_t>(scene.incoming->bytes() - before, 1));
    if (!done) continue;
    if (scene.incoming->failed()) {
      status_.report(ErrorKind::content, key + ": " + scene.incoming->error());
      scene.incoming.reset();
      continue;
    }
    if (scene.gpu) ++swaps_;
    scene.gpu = std::move(scene.incoming);
    scene.pose = scene.gpu->rig() ? std::make_unique<scene::Pose>(scene.gpu->rig()) : nullptr;
    for (size_t i = 0; i < keys_.size(); ++i)
      if (keys_[i] == key) selections_[i] = kUnresolved;  // a new version may name its animations anew
    scene.bounds = scene.incoming_bounds;
    scene.cameras = std::move(scene.incoming_cameras);
    scene.display = scene.incoming_display;
    shown_swapped = shown_swapped || key == shown;
  }
  return shown_swapped;
}

const CachedScene* SceneCache::ready(int item) const {
  const auto found = scenes_.find(key_of(item));
  if (found == scenes_.end() || !found->second.gpu || !found->second.gpu->ready()) return nullptr;
  return &found->second;
}

bool SceneCache::settled(int item) const {
  const auto found = scenes_.find(key_of(item));
  if (found == scenes_.end()) return false;
  const CachedScene& scene = found->second;
  return !scene.error.empty() || (scene.gpu && scene.gpu->ready() && !scene.incoming);
}

void SceneCache::pose(int item, double item_time) {
  const size_t i = static_cast<size_t>(item);
  const auto found = scenes_.find(keys_[i]);
  if (found == scenes_.end() || !found->second.gpu) return;
  CachedScene& scene = found->second;
  int& selection = selections_[i];
  if (selection == kUnresolved) {
    std::string error;
    const scene::Rig* rig = scene.gpu->rig().get();
    if (!scene::select_animation(rig, animation_specs_[i], selection, error)) {
      status_.report(ErrorKind::content,
                     keys_[i] + ": item[" + std::to_string(i) + "].animation: " + error + "; the scene is shown at rest");
      selection = scene::Rig::kNoAnimation;
    }
  }
  if (!scene.pose) return;
  scene.pose->at(selection, item_time * animation_speeds_[i]);
  scene.gpu->pose(*scene.pose);  // the draws and the lights
  scene::pose_cameras(scene.cameras, *scene.pose);
}

void SceneCache::reload_all() {
  for (const auto& [key, scene] : scenes_) loader_.load_scene(key);
}

void SceneCache::reload(const std::string& path) {
  // A deleted scene, display or environment fails to load and is reported; the last good version keeps playing.
  for (const auto& [key, scene] : scenes_)
    if (scene_of(key) == path || display_of(key) == path || environment_of(key) == path) loader_.load_scene(key);
}

void SceneCache::append_warnings(std::vector<std::string>& out) const {
  for (const auto& [key, scene] : scenes_) out.insert(out.end(), scene.warnings.begin(), scene.warnings.end());
}

}  // namespace app
