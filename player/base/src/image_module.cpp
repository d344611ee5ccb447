// The image module (libssao-player-images.so): base/image_codec.h's reader and writer over
// OpenImageIO. Loaded by base/src/image_codec.cpp on first use; nothing else links OpenImageIO
// into the player.
#include "base/image_codec.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

namespace base::images {
namespace {

// OpenImageIO keeps a message per thread when a call fails; each is taken as it comes so that
// none surfaces later in another call's words.
std::string take_global_error() {
  return OIIO::geterror();
}

class OiioReader final : public Reader {
 public:
  explicit OiioReader(std::unique_ptr<OIIO::ImageInput> fixed) : input_(std::move(fixed)), fixed_(input_ != nullptr) {}
  ~OiioReader() override { close(); }

  bool open(const std::string& name, const void* bytes, std::size_t size, Header& header, std::string& error) override {
    close();
    memory_ = std::make_unique<OIIO::Filesystem::IOMemReader>(const_cast<void*>(bytes), size);
    OIIO::ImageSpec spec;
    if (fixed_) {
      input_->set_ioproxy(memory_.get());
      if (!input_->open(name, spec, OIIO::ImageSpec())) {
        error = input_->geterror();
        take_global_error();
        input_->set_ioproxy(nullptr);
        return false;
      }
    } else {
      input_ = OIIO::ImageInput::open(name, nullptr, memory_.get());
      if (!input_) {
        error = take_global_error();
        return false;
      }
      spec = input_->spec();
    }
    open_ = true;
    header.width = spec.width;
    header.height = spec.height;
    header.depth = spec.depth;
    header.channels = spec.nchannels;
    header.floating = spec.format.is_floating_point();
    return true;
  }

  bool read(int channels, std::uint8_t* pixels, std::size_t pixel_stride, std::string& messages) override {
    const OIIO::stride_t x_stride = pixel_stride == 0 ? OIIO::AutoStride : static_cast<OIIO::stride_t>(pixel_stride);
    const bool read = open_ && input_->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels, x_stride);
    messages = take_messages();
    return read;
  }

  bool read(int channels, float* pixels, std::string& messages) override {
    const bool read = open_ && input_->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, pixels);
    messages = take_messages();
    return read;
  }

  void close() override {
    if (open_) input_->close();
    open_ = false;
    if (fixed_ && input_) input_->set_ioproxy(nullptr);
    if (!fixed_) input_.reset();
    memory_.reset();
  }

 private:
  std::string take_messages() {
    std::string text = input_ && input_->has_error() ? input_->geterror() : std::string();
    const std::string global = take_global_error();
    if (text.empty()) text = global;
    return text;
  }

  std::unique_ptr<OIIO::ImageInput> input_;
  std::unique_ptr<OIIO::Filesystem::IOMemReader> memory_;
  bool fixed_ = false;
  bool open_ = false;
};

std::unique_ptr<Reader> make_reader(const std::string& format, std::string& error) {
  if (format.empty()) return std::make_unique<OiioReader>(nullptr);
  std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::create(format);
  if (!input) {
    error = "OpenImageIO has no " + format + " reader (" + take_global_error() + ")";
    return nullptr;
  }
  return std::make_unique<OiioReader>(std::move(input));
}

WriteFailure write(const std::string& path, const WriteSpec& spec, const void* pixels, std::string& error) {
  auto output = OIIO::ImageOutput::create(path);
  if (!output) {
    error = take_global_error();
    return WriteFailure::no_writer;
  }
  const OIIO::TypeDesc type = spec.floating ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8;
  OIIO::ImageSpec image(spec.width, spec.height, spec.channels, type);
  if (!spec.channel_names.empty()) image.channelnames = spec.channel_names;
  if (!spec.compression.empty()) image.attribute("compression", spec.compression);
  if (!output->open(path, image)) {
    error = output->geterror();
    take_global_error();
    return WriteFailure::open;
  }
  const OIIO::stride_t row = spec.row_stride == 0 ? OIIO::AutoStride : static_cast<OIIO::stride_t>(spec.row_stride);
  if (!output->write_image(type, pixels, OIIO::AutoStride, row) || !output->close()) {
    error = output->geterror();
    take_global_error();
    return WriteFailure::write;
  }
  return WriteFailure::none;
}

const Codec kCodec{make_reader, write, "OpenImageIO " OIIO_VERSION_STRING};

}  // namespace
}  // namespace base::images

extern "C" __attribute__((visibility("default"))) const base::images::Codec* player_image_codec_v1() {
  return &base::images::kCodec;
}
