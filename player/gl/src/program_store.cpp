#include "gl/program_store.h"

#include "gl/gl_api.h"

#include <unistd.h>
#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <system_error>

namespace gl {
namespace {

namespace fs = std::filesystem;

// A file: this header, then the driver's binary. The key check is a second, independent hash of the
// texts and the driver (the first names the file), so a collision of one is not enough to load a
// program for other sources; the checksum finds a damaged or truncated binary before the driver sees it.
constexpr char kMagic[8] = {'S', 'S', 'A', 'O', 'P', 'R', 'G', '1'};
struct Header {
  char magic[8];
  std::uint32_t format;  // the driver's binary format (GL_PROGRAM_BINARY_FORMAT)
  std::uint32_t length;  // bytes of binary after the header
  std::uint64_t key_check;
  std::uint64_t checksum;
};

std::uint64_t fnv1a(std::uint64_t hash, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 0x100000001b3ull;
  return hash;
}

std::uint64_t mix(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

// A multiply-rotate hash over 8-byte words: unrelated to FNV-1a, so the two do not collide together.
std::uint64_t word_hash(std::uint64_t hash, const std::string& text) {
  std::size_t i = 0;
  for (; i + 8 <= text.size(); i += 8) {
    std::uint64_t word = 0;
    std::memcpy(&word, text.data() + i, 8);
    hash = mix(hash ^ word) + 0x9e3779b97f4a7c15ull;
  }
  std::uint64_t tail = text.size() - i;
  for (; i < text.size(); ++i) tail = (tail << 8) | static_cast<unsigned char>(text[i]);
  return mix(hash ^ tail ^ (text.size() << 1));
}

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
  return key_hash(0xcbf29ce484222325ull, driver, sources,
                  [](std::uint64_t h, const std::string& s) { return fnv1a(h, s.data(), s.size() + 1); });
}

std::uint64_t check_key(const std::string& driver, const std::vector<StageSource>& sources) {
  return key_hash(0x5eed5eed5eed5eedull, driver, sources, word_hash);
}

// Oldest first by modification time, which load() renews: least recently used first.
void prune(const fs::path& dir) {
  struct Entry {
    fs::path path;
    fs::file_time_type time;
    std::uintmax_t size;
  };
  std::vector<Entry> entries;
  std::uintmax_t total = 0;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    // Every file counts, so that the leftovers of a save cut short are bounded too.
    if (!entry.is_regular_file(ec)) continue;
    entries.push_back({entry.path(), entry.last_write_time(ec), entry.file_size(ec)});
    total += entries.back().size;
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.time < b.time; });
  for (std::size_t i = 0; i < entries.size() && (entries.size() - i > ProgramStore::kMaxFiles || total > ProgramStore::kMaxBytes);
       ++i) {
    fs::remove(entries[i].path, ec);
    total -= entries[i].size;
  }
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
  prune(dir);
  std::unique_ptr<ProgramStore> store(new ProgramStore());
  store->dir_ = dir;
  store->driver_ = caps.renderer + "\n" + caps.version + "\n" + caps.shading_language;
  return store;
}

std::string ProgramStore::path_for(const std::vector<StageSource>& sources) const {
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.bin", static_cast<unsigned long long>(file_key(driver_, sources)));
  return (fs::path(dir_) / name).string();
}

Program ProgramStore::load(const std::vector<StageSource>& sources) {
  const std::string path = path_for(sources);
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  const auto reject = [&] {
    ++rejected_;
    std::error_code ec;
    fs::remove(path, ec);
    return Program();
  };
  Header header{};
  if (bytes.size() < sizeof header) return reject();
  std::memcpy(&header, bytes.data(), sizeof header);
  const char* binary = bytes.data() + sizeof header;
  if (std::memcmp(header.magic, kMagic, sizeof kMagic) != 0 || header.length != bytes.size() - sizeof header ||
      header.key_check != check_key(driver_, sources) || header.checksum != fnv1a(0xcbf29ce484222325ull, binary, header.length))
    return reject();
  Program program(api.CreateProgram());
  api.ProgramBinary(program.id(), header.format, binary, static_cast<GLsizei>(header.length));
  GLint ok = GL_FALSE;
  api.GetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  while (api.GetError() != GL_NO_ERROR) ok = GL_FALSE;  // an unknown format is GL_INVALID_ENUM
  if (ok != GL_TRUE) return reject();
  std::error_code ec;
  fs::last_write_time(path, fs::file_time_type::clock::now(), ec);
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
  std::string bytes(sizeof(Header) + static_cast<std::size_t>(length), '\0');
  GLenum format = 0;
  GLsizei written = 0;
  api.GetProgramBinary(program.id(), length, &written, &format, bytes.data() + sizeof(Header));
  if (written <= 0) {
    error = "the driver gave no binary for " + sources.front().file;
    return false;
  }
  bytes.resize(sizeof(Header) + static_cast<std::size_t>(written));
  Header header{};
  std::memcpy(header.magic, kMagic, sizeof kMagic);
  header.format = format;
  header.length = static_cast<std::uint32_t>(written);
  header.key_check = check_key(driver_, sources);
  header.checksum = fnv1a(0xcbf29ce484222325ull, bytes.data() + sizeof(Header), header.length);
  std::memcpy(bytes.data(), &header, sizeof header);

  // Written beside, then renamed over: a reader (another player starting) sees the old file or the
  // whole new one.
  const std::string path = path_for(sources);
  const std::string partial = path + ".partial." + std::to_string(getpid());
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      error = "cannot write " + partial;
      std::error_code ec;
      fs::remove(partial, ec);
      return false;
    }
  }
  std::error_code ec;
  fs::rename(partial, path, ec);
  if (ec) {
    error = "cannot rename " + partial + " to " + path + ": " + ec.message();
    fs::remove(partial, ec);
    return false;
  }
  return true;
}

}  // namespace gl
