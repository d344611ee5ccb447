#include "environment_cache.h"

#include "base/cache_file.h"

#include <atomic>
#include <cstdint>
#include <cstring>
#include <mutex>
#include <string>
#include <system_error>

namespace scene {
namespace {

namespace fs = std::filesystem;

// A file: this header, then the nine SH coefficients and every level's faces, as floats. Named by
// one hash of the key (the build, the sizes and the image), checked by a second one; the checksum
// finds a damaged or truncated file.
constexpr char kMagic[8] = {'S', 'S', 'A', 'O', 'E', 'N', 'V', '1'};
struct Header {
  char magic[8];
  std::uint32_t face_size;
  std::uint32_t levels;
  std::uint64_t key_check;
  std::uint64_t length;  // bytes after the header
  std::uint64_t checksum;
};

std::mutex dir_mutex;
fs::path kept_dir;         // empty: none kept
std::string keep_problem;  // guarded by dir_mutex too
std::atomic<std::size_t> prepared_count{0}, loaded_count{0}, rejected_count{0};

fs::path dir() {
  const std::lock_guard lock(dir_mutex);
  return kept_dir;
}

// Everything that decides the result: the build that computes it, the sizes and the pixels.
std::string key_text(int width, int height, const std::vector<float>& rgb, int face_size, int levels) {
  std::string text = base::executable_build_id() + "\n" + std::to_string(width) + "x" + std::to_string(height) + " " +
                     std::to_string(face_size) + " " + std::to_string(levels) + "\n";
  text.append(reinterpret_cast<const char*>(rgb.data()), rgb.size() * sizeof(float));
  return text;
}

fs::path file_for(const fs::path& folder, const std::string& key) {
  return folder / base::cache_file_name(base::fnv1a(base::kFnvOffset, key.data(), key.size()), ".env");
}

std::uint64_t check_of(const std::string& key) {
  return base::word_hash(0x5eed5eed5eed5eedull, key);
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
  if (folder.empty() || base::executable_build_id().empty()) {
    ++prepared_count;
    return std::nullopt;
  }
  const std::string key = key_text(width, height, rgb, face_size, levels);
  const fs::path path = file_for(folder, key);
  std::string bytes;
  if (!base::read_cache_file(path, bytes)) {
    ++prepared_count;
    return std::nullopt;
  }
  const std::size_t floats = payload_floats(face_size, levels);
  Header header{};
  if (bytes.size() >= sizeof header) std::memcpy(&header, bytes.data(), sizeof header);
  const char* payload = bytes.data() + sizeof header;
  if (bytes.size() != sizeof header + floats * sizeof(float) || std::memcmp(header.magic, kMagic, sizeof kMagic) != 0 ||
      header.face_size != std::uint32_t(face_size) || header.levels != std::uint32_t(levels) || header.key_check != check_of(key) ||
      header.length != floats * sizeof(float) || header.checksum != base::fnv1a(base::kFnvOffset, payload, header.length)) {
    std::error_code ec;
    fs::remove(path, ec);
    ++rejected_count;
    ++prepared_count;
    return std::nullopt;
  }
  Environment env;
  env.face_size = face_size;
  std::memcpy(env.irradiance_sh.data(), payload, sizeof env.irradiance_sh);
  payload += sizeof env.irradiance_sh;
  for (int l = 0; l < levels; ++l) {
    std::vector<float>& level = env.specular.emplace_back(std::size_t(6) * std::size_t(face_size >> l) * std::size_t(face_size >> l) * 3);
    std::memcpy(level.data(), payload, level.size() * sizeof(float));
    payload += level.size() * sizeof(float);
  }
  ++loaded_count;
  return env;
}

void keep_environment(int width, int height, const std::vector<float>& rgb, const Environment& env) {
  const fs::path folder = dir();
  if (folder.empty() || base::executable_build_id().empty()) return;
  const std::string key = key_text(width, height, rgb, env.face_size, env.levels());
  Header header{};
  std::memcpy(header.magic, kMagic, sizeof kMagic);
  header.face_size = std::uint32_t(env.face_size);
  header.levels = std::uint32_t(env.levels());
  header.key_check = check_of(key);
  std::string bytes(sizeof header, '\0');
  bytes.append(reinterpret_cast<const char*>(env.irradiance_sh.data()), sizeof env.irradiance_sh);
  for (const std::vector<float>& level : env.specular)
    bytes.append(reinterpret_cast<const char*>(level.data()), level.size() * sizeof(float));
  header.length = bytes.size() - sizeof header;
  header.checksum = base::fnv1a(base::kFnvOffset, bytes.data() + sizeof header, header.length);
  std::memcpy(bytes.data(), &header, sizeof header);
  std::error_code ec;
  fs::create_directories(folder, ec);
  std::string error;
  if (ec)
    error = "cannot make " + folder.string() + ": " + ec.message();
  else if (base::write_file_whole(file_for(folder, key), bytes, error))
    return;
  const std::lock_guard lock(dir_mutex);
  keep_problem = error;
}

}  // namespace detail
}  // namespace scene
