#pragma once
// Reads scenes and playlists on a thread of its own, so parsing, validating and decoding images
// never holds up a frame. Results come back through a queue; fd() (an eventfd) wakes the loop.
#include "base/unique_fd.h"
#include "lightfield/display_file.h"
#include "playback/playlist.h"
#include "scene/environment.h"
#include "scene/gltf_loader.h"
#include "scene/load.h"
#include "scene/scene.h"

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace app {

// The loader's key for a playlist item: its scene, then its display and its environment when it
// has them (`fallback_environment` when the item names none), one per line.
inline std::string load_key(const playback::Item& item, const std::string& fallback_environment = {}) {
  const std::string& environment = item.environment.empty() ? fallback_environment : item.environment;
  if (item.display.empty() && environment.empty()) return item.scene;
  return item.scene + "\n" + item.display + (environment.empty() ? "" : "\n" + environment);
}
// The scene spec, the display path and the environment of a key (empty where it has none).
inline std::string key_part(const std::string& key, int part) {
  size_t begin = 0;
  for (int i = 0; i < part; ++i) {
    begin = key.find('\n', begin);
    if (begin == std::string::npos) return {};
    ++begin;
  }
  return key.substr(begin, key.find('\n', begin) - begin);
}
inline std::string scene_of(const std::string& key) {
  return key_part(key, 0);
}
inline std::string display_of(const std::string& key) {
  return key_part(key, 1);
}
inline std::string environment_of(const std::string& key) {
  return key_part(key, 2);
}

class Loader {
 public:
  struct Result {
    enum class Kind : std::uint8_t { scene, playlist } kind = Kind::scene;
    std::string path;  // the scene key (see load_scene) or the playlist file, as requested
    std::shared_ptr<const scene::Scene> scene;
    std::shared_ptr<const lightfield::Display> display;  // when the key names one
    std::shared_ptr<const playback::Playlist> playlist;
    std::string error;                  // empty on success
    std::vector<std::string> warnings;  // "spec: what" for what loaded anyway (a texture drawn white)
    double seconds = 0.0;               // the load on the loader thread: read, decoded, checked
  };

  explicit Loader(playback::ParseOptions playlist_options);
  ~Loader();
  Loader(const Loader&) = delete;
  Loader& operator=(const Loader&) = delete;

  int fd() const { return wake_.get(); }
  // What scenes are loaded with from now on (the GL context's largest texture, once it exists).
  void set_scene_options(const scene::LoadOptions& options);
  // `key`: a scene spec, or "SPEC\nDISPLAY[\nENVIRONMENT]" (load_key): a display file is read too,
  // and for optical modules the scene's long edges are split for it; an environment is prepared
  // (once per file version) and given to the scene.
  void load_scene(const std::string& key);
  void load_playlist(const std::string& path);
  // Non-blocking: the oldest finished job, if any.
  bool take(Result& out);
  // Jobs queued or running.
  std::size_t busy() const;

 private:
  void run();

  playback::ParseOptions playlist_options_;
  scene::LoadOptions scene_options_;  // guarded by mutex_
  // The loader thread's own: environments prepared so far, by path and file version.
  std::map<std::string, std::weak_ptr<const scene::Environment>> environments_;
  bool environment(const std::string& spec, std::shared_ptr<const scene::Environment>& out, std::string& error);
  base::UniqueFd wake_;
  mutable std::mutex mutex_;
  std::condition_variable work_;
  std::deque<Result> jobs_, done_;
  std::size_t running_ = 0;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace app
