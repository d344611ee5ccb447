#include "base/read_file.h"

#include "base/errno_text.h"
#include "base/unique_fd.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>

namespace base {
namespace {

std::string_view kind_of(mode_t mode) {
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// "3073 bytes", "1.5 MiB (1572864 bytes)": exact, so a file just over a limit does not read as equal to it.
std::string exact_size_text(std::size_t bytes) {
  return bytes < kKiB ? byte_size_text(bytes) : byte_size_text(bytes) + " (" + std::to_string(bytes) + " bytes)";
}

// Opens `path` for reading, refusing anything but a regular file of at most `max_bytes`; the size
// it had in `size`.
UniqueFd open_regular(const std::string& path, std::string_view what, std::size_t max_bytes, std::size_t& size,
                      std::string& error) {
  UniqueFd fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
  if (!fd) {
    error = path + ": cannot open the " + std::string(what) + " (" + errno_text(errno) + ")";
    return {};
  }
  struct stat st {};
  if (::fstat(fd.get(), &st) != 0) {
    error = path + ": cannot read the " + std::string(what) + " (" + errno_text(errno) + ")";
    return {};
  }
  if (!S_ISREG(st.st_mode)) {
    error = path + ": the " + std::string(what) + " is " + std::string(kind_of(st.st_mode)) + ", not a regular file";
    return {};
  }
  size = static_cast<std::size_t>(st.st_size);
  if (size > max_bytes) {
    error = path + ": the " + std::string(what) + " is " + exact_size_text(size) + "; at most " + exact_size_text(max_bytes) +
            " is read";
    return {};
  }
  return fd;
}

}  // namespace

std::string byte_size_text(std::size_t bytes) {
  if (bytes < kKiB) return std::to_string(bytes) + " bytes";
  const char* unit = bytes < kMiB ? "KiB" : bytes < kGiB ? "MiB" : "GiB";
  const double scale = static_cast<double>(bytes < kMiB ? kKiB : bytes < kGiB ? kMiB : kGiB);
  char text[48];
  std::snprintf(text, sizeof text, "%.1f %s", static_cast<double>(bytes) / scale, unit);
  return text;
}

bool read_regular_file(const std::string& path, std::string_view what, std::size_t max_bytes, std::string& out,
                       std::string& error) {
  std::size_t size = 0;
  const UniqueFd fd = open_regular(path, what, max_bytes, size, error);
  if (!fd) return false;
  out.clear();
  out.resize(size);
  std::size_t got = 0;
  // A file that grows while it is read is read to the size fstat gave plus one byte, so the growth
  // is noticed and the bound still holds.
  for (;;) {
    if (got == out.size()) {
      if (out.size() >= max_bytes) break;
      out.resize(std::min(max_bytes, out.size() + 64 * kKiB));
    }
    const ssize_t n = ::read(fd.get(), out.data() + got, out.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      error = path + ": cannot read the " + std::string(what) + " (" + errno_text(errno) + ")";
      out.clear();
      return false;
    }
    if (n == 0) break;
    got += static_cast<std::size_t>(n);
  }
  out.resize(got);
  if (got >= max_bytes && got > size) {
    error = path + ": the " + std::string(what) + " grew past " + byte_size_text(max_bytes) + " while it was read";
    out.clear();
    return false;
  }
  return true;
}

}  // namespace base
