#include "unpack.h"

#include "base/read_file.h"

#include <archive.h>
#include <archive_entry.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <vector>

namespace content {
namespace fs = std::filesystem;
namespace {

void fnv(std::uint64_t& hash, const void* data, std::size_t size) {
  const auto* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) hash = (hash ^ bytes[i]) * 0x100000001b3ull;
}

bool hidden(const fs::path& relative) {
  return std::any_of(relative.begin(), relative.end(), [](const fs::path& part) {
    const std::string name = part.string();
    return !name.empty() && name.front() == '.';
  });
}

std::string over_budget(const std::string& source, std::uint64_t max_bytes) {
  return source + ": the bundle is over its size budget of " + base::byte_size_text(max_bytes) + " (--max-size)";
}

}  // namespace

bool copy_folder(const std::string& source, const std::string& target, std::uint64_t max_bytes, Unpacked& unpacked,
                 std::string& error) {
  std::error_code ec;
  std::vector<char> buffer(1 << 20);
  for (fs::recursive_directory_iterator it(source, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path relative = it->path().lexically_relative(source);
    if (hidden(relative)) {
      if (it->is_directory(ec)) it.disable_recursion_pending();
      continue;
    }
    const fs::file_status status = it->symlink_status(ec);
    if (fs::is_directory(status)) {
      fs::create_directories(fs::path(target) / relative, ec);
    } else if (fs::is_regular_file(status)) {
      std::ifstream in(it->path(), std::ios::binary);
      std::ofstream out(fs::path(target) / relative, std::ios::binary);
      while (in && out) {
        in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        const auto got = static_cast<std::size_t>(in.gcount());
        if (got == 0) break;
        unpacked.bytes += got;
        if (unpacked.bytes > max_bytes) {
          error = over_budget(source, max_bytes);
          return false;
        }
        out.write(buffer.data(), static_cast<std::streamsize>(got));
      }
      if (in.bad() || !out.flush()) {
        error = it->path().string() + ": cannot copy it (" + (in.bad() ? "read" : "write") + " failed)";
        return false;
      }
      ++unpacked.files;
    } else {
      error = it->path().string() + ": " + (fs::is_symlink(status) ? "a symbolic link" : "not a regular file") +
              "; a bundle holds regular files and folders only";
      return false;
    }
  }
  if (ec) {
    error = source + ": cannot read the folder (" + ec.message() + ")";
    return false;
  }
  return true;
}

bool unpack_tar(const std::string& source, const std::string& target, std::uint64_t max_bytes, Unpacked& unpacked,
                std::string& error) {
  const std::unique_ptr<archive, int (*)(archive*)> reader(archive_read_new(), archive_read_free);
  archive_read_support_filter_all(reader.get());
  archive_read_support_format_tar(reader.get());
  if (archive_read_open_filename(reader.get(), source.c_str(), 1 << 16) != ARCHIVE_OK) {
    error = source + ": cannot open the tar (" + archive_error_string(reader.get()) + ")";
    return false;
  }
  archive_entry* entry = nullptr;
  int status = ARCHIVE_OK;
  while ((status = archive_read_next_header(reader.get(), &entry)) == ARCHIVE_OK) {
    const char* raw_name = archive_entry_pathname(entry);
    const fs::path name = fs::path(raw_name != nullptr ? raw_name : "").lexically_normal();
    const std::string shown = source + ": " + (raw_name != nullptr ? raw_name : "(no name)");
    if (name.empty() || name.is_absolute() || *name.begin() == "..") {
      error = shown + ": a path outside the bundle";
      return false;
    }
    if (name == "." || hidden(name)) continue;
    const fs::path out_path = fs::path(target) / name;
    std::error_code ec;
    switch (archive_entry_filetype(entry)) {
      case AE_IFDIR:
        fs::create_directories(out_path, ec);
        break;
      case AE_IFREG: {
        fs::create_directories(out_path.parent_path(), ec);
        std::ofstream out(out_path, std::ios::binary);
        const void* block = nullptr;
        std::size_t size = 0;
        la_int64_t offset = 0;
        int read = ARCHIVE_OK;
        while ((read = archive_read_data_block(reader.get(), &block, &size, &offset)) == ARCHIVE_OK) {
          unpacked.bytes += size;
          if (unpacked.bytes > max_bytes) {
            error = over_budget(source, max_bytes);
            return false;
          }
          out.write(static_cast<const char*>(block), static_cast<std::streamsize>(size));
        }
        if (read != ARCHIVE_EOF || !out.flush()) {
          error =
              shown + ": cannot unpack it (" + (read != ARCHIVE_EOF ? archive_error_string(reader.get()) : "write failed") + ")";
          return false;
        }
        ++unpacked.files;
        break;
      }
      default:
        error = shown + ": not a regular file or folder (a link or a device); a bundle holds regular files and folders only";
        return false;
    }
    if (ec) {
      error = shown + ": cannot write it (" + ec.message() + ")";
      return false;
    }
  }
  if (status != ARCHIVE_EOF) {
    error = source + ": a damaged tar (" + archive_error_string(reader.get()) + ")";
    return false;
  }
  return true;
}

bool hash_folder(const std::string& folder, std::uint64_t& hash, std::string& error) {
  std::error_code ec;
  std::map<std::string, fs::path> files;
  for (fs::recursive_directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file(ec)) files[it->path().lexically_relative(folder).generic_string()] = it->path();
  hash = 0xcbf29ce484222325ull;
  std::vector<char> buffer(1 << 20);
  for (const auto& [name, path] : files) {
    fnv(hash, name.data(), name.size() + 1);
    std::ifstream in(path, std::ios::binary);
    while (in) {
      in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      fnv(hash, buffer.data(), static_cast<std::size_t>(in.gcount()));
    }
    if (in.bad()) {
      error = path.string() + ": cannot read it back";
      return false;
    }
  }
  return !ec;
}

}  // namespace content
