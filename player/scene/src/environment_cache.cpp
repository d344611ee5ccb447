#include "environment_cache.h"

#include "base/cache_file.h"

#include <atomic>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <string>
#include <string_view>
#include <system_error>

namespace scene {
namespace {

namespace fs = std::filesystem;

// A sealed cache file (base/cache_file.h) whose payload is the nine SH coefficients and every
// level's faces, as floats. Named by one hash of the key (the build, the sizes and the image) and
// checked by a second; the checksum finds a damaged or truncated file.
constexpr std::string_view kMagic = "SSAOENV1";

std::mutex dir_mutex;
fs::path kept_dir;         // empty: none kept
std::string keep_problem;  // guarded by dir_mutex too
std::atomic<std::size_t> prepared_count{0}, loaded_count{0}, rejected_count{0};

fs::path dir() {
  const std::lock_guard lock(dir_mutex);
  return kept_dir;
}

// Everything that decides the result (the build that computes it, the sizes and the pixels) under
// the two hashes: `name` names the file, `check` is kept in it. The pixels are hashed where they lie:
// an image may be hundreds of megabytes.
struct Key {
  std::uint64_t name, check;
};
Key key_of(int width, int height, const std::vector<float>& rgb, int face_size, int levels) {
  const std::string sizes = base::executable_build_id() + "\n" + std::to_string(width) + "x" + std::to_string(height) + " " +
                            std::to_string(face_size) + " " + std::to_string(levels) + "\n";
  const std::string_view pixels(reinterpret_cast<const char*>(rgb.data()), rgb.size() * sizeof(float));
  return {base::fnv1a(base::fnv1a(base::kFnvOffset, sizes.data(), sizes.size()), pixels.data(), pixels.size()),
          base::word_hash(base::word_hash(0x5eed5eed5eed5eedull, sizes), pixels)};
}

fs::path file_for(const fs::path& folder, const Key& key) {
  return folder / base::cache_file_name(key.name, ".env");
}

std::size_t payload_floats(int face_size, int levels) {
  std::size_t n = 27;
  for (int l = 0; l < levels; ++l) n += std::size_t(6) * std::size_t(face_size >> l) * std::size_t(face_size >> l) * 3;
  return n;
}

}  // namespace

void keep_prepared_environments(const std::filesystem::path& folder) {
  {
    const std::lock_guard lock(dir_mutex);
    kept_dir = folder;
    keep_problem.clear();
  }
  if (!folder.empty()) base::prune_least_recent(folder, kMaxKeptEnvironments, kMaxKeptEnvironmentBytes);
}

EnvironmentCacheCounts environment_cache_counts() {
  const std::lock_guard lock(dir_mutex);
  return {prepared_count.load(), loaded_count.load(), rejected_count.load(), kept_dir, keep_problem};
}

namespace detail {

std::optional<Environment> kept_environment(int width, int height, const std::vector<float>& rgb, int face_size, int levels) {
  const fs::path folder = dir();
  // A build without an id cannot tell its files from another build's: it keeps none.
  if (folder.empty() || base::executable_build_id().empty()) return std::nullopt;
  const Key key = key_of(width, height, rgb, face_size, levels);
  const fs::path path = file_for(folder, key);
  std::string bytes;
  if (!base::read_cache_file(path, bytes)) return std::nullopt;
  const std::optional<std::string_view> sealed = base::unseal_cache_payload(bytes, kMagic, key.check);
  if (!sealed || sealed->size() != payload_floats(face_size, levels) * sizeof(float)) {
    std::error_code ec;
    fs::remove(path, ec);
    ++rejected_count;
    return std::nullopt;
  }
  const char* payload = sealed->data();
  Environment env;
  env.face_size = face_size;
  std::memcpy(env.irradiance_sh.data(), payload, sizeof env.irradiance_sh);
  payload += sizeof env.irradiance_sh;
  for (int l = 0; l < levels; ++l) {
    std::vector<float>& level =
        env.specular.emplace_back(std::size_t(6) * std::size_t(face_size >> l) * std::size_t(face_size >> l) * 3);
    std::memcpy(level.data(), payload, level.size() * sizeof(float));
    payload += level.size() * sizeof(float);
  }
  ++loaded_count;
  return env;
}

void keep_environment(int width, int height, const std::vector<float>& rgb, const Environment& env) {
  ++prepared_count;
  const fs::path folder = dir();
  if (folder.empty() || base::executable_build_id().empty()) return;
  const Key key = key_of(width, height, rgb, env.face_size, env.levels());
  std::string payload(reinterpret_cast<const char*>(env.irradiance_sh.data()), sizeof env.irradiance_sh);
  for (const std::vector<float>& level : env.specular)
    payload.append(reinterpret_cast<const char*>(level.data()), level.size() * sizeof(float));
  std::error_code ec;
  fs::create_directories(folder, ec);
  std::string error;
  if (ec)
    error = "cannot make " + folder.string() + ": " + ec.message();
  else if (base::write_file_whole(file_for(folder, key), base::seal_cache_payload(kMagic, key.check, payload), error))
    return;
  const std::lock_guard lock(dir_mutex);
  keep_problem = error;
}

}  // namespace detail
}  // namespace scene
