#include "loader.h"

#include "render/light_field.h"
#include "scene/load.h"

#include <sys/eventfd.h>

#include <chrono>
#include <sstream>

namespace app {

Loader::Loader(playback::ParseOptions playlist_options)
    : playlist_options_(std::move(playlist_options)), wake_(eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC)) {
  thread_ = std::thread([this] { run(); });
}

Loader::~Loader() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  work_.notify_all();
  thread_.join();
}

void Loader::set_scene_options(const scene::LoadOptions& options) {
  std::lock_guard lock(mutex_);
  scene_options_ = options;
}

void Loader::load_scene(const std::string& key) {
  {
    std::lock_guard lock(mutex_);
    jobs_.push_back({Result::Kind::scene, key, nullptr, nullptr, nullptr, {}, {}, 0.0});
  }
  work_.notify_one();
}

void Loader::load_playlist(const std::string& path) {
  {
    std::lock_guard lock(mutex_);
    jobs_.push_back({Result::Kind::playlist, path, nullptr, nullptr, nullptr, {}, {}, 0.0});
  }
  work_.notify_one();
}

bool Loader::take(Result& out) {
  uint64_t count = 0;
  (void)!read(wake_.get(), &count, sizeof count);  // re-armed below while results remain
  std::lock_guard lock(mutex_);
  if (done_.empty()) return false;
  out = std::move(done_.front());
  done_.pop_front();
  if (!done_.empty()) {
    const uint64_t one = 1;
    (void)!write(wake_.get(), &one, sizeof one);
  }
  return true;
}

std::size_t Loader::busy() const {
  std::lock_guard lock(mutex_);
  return jobs_.size() + running_;
}

bool Loader::environment(const std::string& spec, std::shared_ptr<const scene::Environment>& out, std::string& error) {
  // Prepared once per file version: items sharing an environment share its memory and its
  // prefiltering, and an edited file is prepared anew.
  std::error_code ec;
  const auto stamp = std::filesystem::last_write_time(spec, ec);
  const std::string version = ec ? spec
                                 : spec + "@" + std::to_string(stamp.time_since_epoch().count()) + "/" +
                                       std::to_string(std::filesystem::file_size(spec, ec));
  // Held weakly: an environment no loaded scene uses any more is freed, not kept for the process.
  std::erase_if(environments_, [](const auto& entry) { return entry.second.expired(); });
  if (const auto found = environments_.find(version); found != environments_.end()) {
    out = found->second.lock();
    if (out) return true;
  }
  if (!scene::load_environment_spec(spec, out, error)) return false;
  if (!ec) environments_[version] = out;
  return true;
}

void Loader::run() {
  for (;;) {
    Result job;
    scene::LoadOptions scene_options;
    {
      std::unique_lock lock(mutex_);
      work_.wait(lock, [this] { return stop_ || !jobs_.empty(); });
      if (stop_) return;
      scene_options = scene_options_;
      job = std::move(jobs_.front());
      jobs_.pop_front();
      ++running_;
    }
    const auto started = std::chrono::steady_clock::now();
    if (job.kind == Result::Kind::scene) {
      auto scene = std::make_shared<scene::Scene>();
      std::ostringstream log;  // warnings are not errors: the item plays, and the status says them
      const std::string display_path = display_of(job.path);
      auto display = std::make_shared<lightfield::Display>();
      if (!display_path.empty() && !lightfield::load_display(display_path, *display, job.error)) {
        // the error names the display file and the field
      } else if (scene::load(scene_of(job.path), *scene, job.error, log, scene_options) &&
                 environment(environment_of(job.path), scene->environment, job.error)) {
        if (!display_path.empty()) {
          render::SubdivisionReport report;
          scene = std::make_shared<scene::Scene>(render::prepare_for_display(*scene, *display, report));
          if (report.capped)
            log << "warning: " << scene_of(job.path) << ": on " << display_path << " some long edges stay bent by up to "
                << report.worst_after_px << " px (the triangle budget ran out splitting them)\n";
          job.display = std::move(display);
        }
        job.scene = std::move(scene);
      }
      std::istringstream lines(log.str());
      constexpr std::string_view kPrefix = "warning: ";
      for (std::string line; std::getline(lines, line);)
        job.warnings.push_back(line.rfind(kPrefix, 0) == 0 ? line.substr(kPrefix.size()) : line);
    } else {
      auto playlist = std::make_shared<playback::Playlist>();
      if (playback::load_playlist(job.path, playlist_options_, *playlist, job.error)) job.playlist = std::move(playlist);
    }
    job.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    {
      std::lock_guard lock(mutex_);
      done_.push_back(std::move(job));
      --running_;
    }
    const uint64_t one = 1;
    (void)!write(wake_.get(), &one, sizeof one);
  }
}

}  // namespace app
