#pragma once
// The one way the player reads a file it was given by name: playlists, display files and
// calibrations, board files, button and camera scripts, mock camera images, scenes and the files
// they name. A FIFO with no writer, a device or a directory where a regular file is expected would
// block the player or feed it without end; each is refused before a byte is read, and every read
// is bounded.
#include <cstddef>
#include <string>
#include <string_view>

namespace base {

// The limits of each kind of file, in bytes: far above what a real one needs, low enough that a
// wrong file is refused before it is read into memory.
inline constexpr std::size_t kKiB = 1024, kMiB = 1024 * kKiB, kGiB = 1024 * kMiB;

// Reads all of the regular file `path`, at most `max_bytes` of it, into `out`. The file is opened
// without blocking (O_NONBLOCK: a FIFO without a writer does not wait), checked with fstat, then
// read. False and why, naming the path and `what` the file was to be ("playlist"):
//   "PATH: cannot open the playlist (No such file or directory)"
//   "PATH: the playlist is a FIFO, not a regular file"
//   "PATH: the playlist is 70.0 MiB; at most 64.0 MiB is read"
bool read_regular_file(const std::string& path, std::string_view what, std::size_t max_bytes, std::string& out,
                       std::string& error);

// "1.5 MiB", "312 bytes": sizes in messages.
std::string byte_size_text(std::size_t bytes);

}  // namespace base
