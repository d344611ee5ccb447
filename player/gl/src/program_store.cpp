#include "gl/program_store.h"

#include "gl/gl_api.h"

#include "base/cache_file.h"

#include <unistd.h>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string_view>
#include <system_error>

namespace gl {
namespace {

namespace fs = std::filesystem;

// A sealed cache file (base/cache_file.h) whose payload is the driver's binary format
// (GL_PROGRAM_BINARY_FORMAT, 4 bytes) and the binary. The key check is a second, independent hash of
// the texts and the driver (the first names the file), so a collision of one is not enough to load a
// program for other sources; the checksum finds a damaged or truncated binary before the driver sees it.
constexpr std::string_view kMagic = "SSAOPRG2";

template <typename Hash>
std::uint64_t key_hash(std::uint64_t seed, const std::string& driver, const std::vector<StageSource>& sources, Hash hash) {
  std::uint64_t h = hash(seed, driver);
  for (const StageSource& stage : sources) {
    h = hash(h, std::to_string(stage.type));
    h = hash(h, stage.text);
  }
  return h;
}

std::uint64_t file_key(const std::string& driver, const std::vector<StageSource>& sources) {
  return key_hash(base::kFnvOffset, driver, sources,
                  [](std::uint64_t h, const std::string& s) { return base::fnv1a(h, s.data(), s.size() + 1); });
}

std::uint64_t check_key(const std::string& driver, const std::vector<StageSource>& sources) {
  return key_hash(0x5eed5eed5eed5eedull, driver, sources,
                  [](std::uint64_t h, const std::string& s) { return base::word_hash(h, s); });
}

}  // namespace

std::unique_ptr<ProgramStore> ProgramStore::open(const std::string& dir, const Caps& caps, std::string& reason) {
  GLint formats = 0;
  api.GetIntegerv(GL_NUM_PROGRAM_BINARY_FORMATS, &formats);
  if (formats <= 0) {
    // Mesa offers a format only while its own shader cache is on (MESA_SHADER_CACHE_DISABLE unset).
    reason = "the driver offers no program binary format";
    return nullptr;
  }
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || access(dir.c_str(), W_OK) != 0) {
    reason = "cannot write to " + dir + ": " + (ec ? ec.message() : std::string(std::strerror(errno)));
    return nullptr;
  }
  base::prune_least_recent(dir, kMaxFiles, kMaxBytes);
  std::unique_ptr<ProgramStore> store(new ProgramStore());
  store->dir_ = dir;
  store->driver_ = caps.renderer + "\n" + caps.version + "\n" + caps.shading_language;
  return store;
}

std::string ProgramStore::path_for(const std::vector<StageSource>& sources) const {
  return (fs::path(dir_) / base::cache_file_name(file_key(driver_, sources), ".bin")).string();
}

Program ProgramStore::load(const std::vector<StageSource>& sources) {
  const std::string path = path_for(sources);
  std::string bytes;
  if (!base::read_cache_file(path, bytes)) return {};
  const auto reject = [&] {
    ++rejected_;
    std::error_code ec;
    fs::remove(path, ec);
    return Program();
  };
  const std::optional<std::string_view> payload = base::unseal_cache_payload(bytes, kMagic, check_key(driver_, sources));
  GLenum format = 0;
  if (!payload || payload->size() <= sizeof format) return reject();
  std::memcpy(&format, payload->data(), sizeof format);
  const std::string_view binary = payload->substr(sizeof format);
  Program program(api.CreateProgram());
  api.ProgramBinary(program.id(), format, binary.data(), static_cast<GLsizei>(binary.size()));
  GLint ok = GL_FALSE;
  api.GetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  while (api.GetError() != GL_NO_ERROR) ok = GL_FALSE;  // an unknown format is GL_INVALID_ENUM
  if (ok != GL_TRUE) return reject();
  ++loaded_;
  return program;
}

bool ProgramStore::save(const std::vector<StageSource>& sources, const Program& program, std::string& error) {
  GLint length = 0;
  api.GetProgramiv(program.id(), GL_PROGRAM_BINARY_LENGTH, &length);
  if (length <= 0) {
    error = "the driver gave no binary for " + sources.front().file;
    return false;
  }
  GLenum format = 0;
  std::string payload(sizeof format + static_cast<std::size_t>(length), '\0');
  GLsizei written = 0;
  api.GetProgramBinary(program.id(), length, &written, &format, payload.data() + sizeof format);
  if (written <= 0) {
    error = "the driver gave no binary for " + sources.front().file;
    return false;
  }
  payload.resize(sizeof format + static_cast<std::size_t>(written));
  std::memcpy(payload.data(), &format, sizeof format);
  return base::write_file_whole(path_for(sources), base::seal_cache_payload(kMagic, check_key(driver_, sources), payload), error);
}

}  // namespace gl
