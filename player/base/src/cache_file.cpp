#include "base/cache_file.h"

#include <elf.h>
#include <link.h>
#include <unistd.h>
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>
#include <vector>

namespace base {
namespace {

namespace fs = std::filesystem;

std::uint64_t mix(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

struct SealHeader {
  char magic[8];
  std::uint64_t key_check;
  std::uint64_t length;  // bytes of payload after the header
  std::uint64_t checksum;
};

// The first object dl_iterate_phdr reports is the executable itself.
int find_build_id(dl_phdr_info* info, std::size_t, void* data) {
  auto& id = *static_cast<std::string*>(data);
  for (int i = 0; i < info->dlpi_phnum; ++i) {
    const ElfW(Phdr)& ph = info->dlpi_phdr[i];
    if (ph.p_type != PT_NOTE) continue;
    const auto* p = reinterpret_cast<const unsigned char*>(info->dlpi_addr + ph.p_vaddr);
    const unsigned char* end = p + ph.p_memsz;
    while (p + sizeof(ElfW(Nhdr)) <= end) {
      ElfW(Nhdr) note;
      std::memcpy(&note, p, sizeof note);
      const unsigned char* name = p + sizeof note;
      const unsigned char* desc = name + ((note.n_namesz + 3) & ~3u);
      if (note.n_type == NT_GNU_BUILD_ID && note.n_namesz == 4 && std::memcmp(name, "GNU", 4) == 0 &&
          desc + note.n_descsz <= end) {
        static const char hex[] = "0123456789abcdef";
        for (unsigned k = 0; k < note.n_descsz; ++k) {
          id += hex[desc[k] >> 4];
          id += hex[desc[k] & 15];
        }
        return 1;
      }
      p = desc + ((note.n_descsz + 3) & ~3u);
    }
  }
  return 1;
}

}  // namespace

std::uint64_t fnv1a(std::uint64_t hash, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 0x100000001b3ull;
  return hash;
}

// A multiply-rotate hash over 8-byte words: unrelated to FNV-1a, so the two do not collide together.
std::uint64_t word_hash(std::uint64_t hash, std::string_view bytes) {
  std::size_t i = 0;
  for (; i + 8 <= bytes.size(); i += 8) {
    std::uint64_t word = 0;
    std::memcpy(&word, bytes.data() + i, 8);
    hash = mix(hash ^ word) + 0x9e3779b97f4a7c15ull;
  }
  std::uint64_t tail = bytes.size() - i;
  for (; i < bytes.size(); ++i) tail = (tail << 8) | static_cast<unsigned char>(bytes[i]);
  return mix(hash ^ tail ^ (bytes.size() << 1));
}

std::string seal_cache_payload(std::string_view magic, std::uint64_t key_check, std::string_view payload) {
  SealHeader header{};
  std::memcpy(header.magic, magic.data(), std::min(magic.size(), sizeof header.magic));
  header.key_check = key_check;
  header.length = payload.size();
  header.checksum = fnv1a(kFnvOffset, payload.data(), payload.size());
  std::string bytes(sizeof header, '\0');
  std::memcpy(bytes.data(), &header, sizeof header);
  bytes.append(payload);
  return bytes;
}

std::optional<std::string_view> unseal_cache_payload(std::string_view file, std::string_view magic, std::uint64_t key_check) {
  SealHeader header{};
  if (file.size() < sizeof header) return std::nullopt;
  std::memcpy(&header, file.data(), sizeof header);
  const std::string_view payload = file.substr(sizeof header);
  if (std::string_view(header.magic, sizeof header.magic) != magic.substr(0, sizeof header.magic) ||
      header.key_check != key_check || header.length != payload.size() ||
      header.checksum != fnv1a(kFnvOffset, payload.data(), payload.size()))
    return std::nullopt;
  return payload;
}

std::string cache_file_name(std::uint64_t key, std::string_view suffix) {
  char name[17];
  std::snprintf(name, sizeof name, "%016llx", static_cast<unsigned long long>(key));
  return std::string(name) + std::string(suffix);
}

bool write_file_whole(const fs::path& path, std::string_view bytes, std::string& error) {
  const fs::path partial = path.string() + ".partial." + std::to_string(getpid());
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      error = "cannot write " + partial.string();
      std::error_code ec;
      fs::remove(partial, ec);
      return false;
    }
  }
  std::error_code ec;
  fs::rename(partial, path, ec);
  if (ec) {
    error = "cannot rename " + partial.string() + " to " + path.string() + ": " + ec.message();
    fs::remove(partial, ec);
    return false;
  }
  return true;
}

bool read_cache_file(const fs::path& path, std::string& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  out.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  std::error_code ec;
  fs::last_write_time(path, fs::file_time_type::clock::now(), ec);
  return true;
}

void prune_least_recent(const fs::path& dir, std::size_t max_files, std::uintmax_t max_bytes) {
  struct Entry {
    fs::path path;
    fs::file_time_type time;
    std::uintmax_t size;
  };
  std::vector<Entry> entries;
  std::uintmax_t total = 0;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
    if (!entry.is_regular_file(ec)) continue;
    entries.push_back({entry.path(), entry.last_write_time(ec), entry.file_size(ec)});
    total += entries.back().size;
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) { return a.time < b.time; });
  for (std::size_t i = 0; i < entries.size() && (entries.size() - i > max_files || total > max_bytes); ++i) {
    fs::remove(entries[i].path, ec);
    total -= entries[i].size;
  }
}

const std::string& executable_build_id() {
  static const std::string id = [] {
    std::string found;
    dl_iterate_phdr(find_build_id, &found);
    return found;
  }();
  return id;
}

}  // namespace base
