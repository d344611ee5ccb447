#pragma once
// Image files and in-memory images through OpenImageIO, which lives in a module loaded on first use
// (libssao-player-images.so): linked into the player, its 260 libraries (ffmpeg, OpenCV, GDAL, ...)
// cost every start of the process 0.3 s on a desktop and 7 s in the test VM before main() ran, even
// for a scene with no image at all.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace base::images {

struct Header {
  int width = 0, height = 0, depth = 1, channels = 0;
  bool floating = false;  // the file's pixels are floating point (HDR, EXR), not integers taken as sRGB
};

// Decodes images held in memory, one at a time.
class Reader {
 public:
  virtual ~Reader() = default;
  // Opens `size` bytes at `bytes`, which must outlive the reads. `name`'s extension picks the
  // format first (OpenImageIO tries the others when that fails). False with the decoder's words.
  virtual bool open(const std::string& name, const void* bytes, std::size_t size, Header& header, std::string& error) = 0;
  // The whole image as the first `channels` channels, in 8 bits (sRGB stays sRGB) or as floats,
  // each pixel `pixel_stride` values apart (0: packed). False when the pixels could not be read;
  // `messages` gets what the decoder said either way ("" when nothing: libjpeg decodes a truncated
  // file with only a warning, which callers that want whole images count as a failure).
  virtual bool read(int channels, std::uint8_t* pixels, std::size_t pixel_stride, std::string& messages) = 0;
  virtual bool read(int channels, float* pixels, std::string& messages) = 0;
  virtual void close() = 0;
};

// A reader that picks the format by each name, or, with `format` ("jpg"), one decoder made once and
// reused for every image (a camera's MJPEG frames). Null and why when the module cannot be loaded.
std::unique_ptr<Reader> make_reader(const std::string& format, std::string& error);

struct WriteSpec {
  int width = 0, height = 0, channels = 0;
  bool floating = false;                   // floats (EXR), else 8 bits
  std::vector<std::string> channel_names;  // empty: the format's defaults
  std::string compression;                 // empty: the format's default
  std::ptrdiff_t row_stride = 0;           // bytes from one row to the next as written (negative: bottom-up memory)
};

enum class WriteFailure { none, no_writer, open, write };

// Writes `pixels` to `path` in the format its extension names. On failure says at which step, with
// the encoder's words in `error`.
WriteFailure write(const std::string& path, const WriteSpec& spec, const void* pixels, std::string& error);

// Loads the module now (play does so on a thread of its own after its first frame, so the first
// textured scene or camera frame does not wait for it). False and why when it cannot be loaded.
bool preload(std::string& error);

// "PATH (OpenImageIO VERSION)", or why there is none: for `player info`.
std::string describe();

// What the module exports, in the same build (the types cross the boundary as they are).
struct Codec {
  std::unique_ptr<Reader> (*make_reader)(const std::string& format, std::string& error);
  WriteFailure (*write)(const std::string& path, const WriteSpec& spec, const void* pixels, std::string& error);
  const char* library;  // the library behind it and its version
};

}  // namespace base::images

// The module's one symbol.
extern "C" const base::images::Codec* player_image_codec_v1();
