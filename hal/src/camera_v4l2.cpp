#include <fcntl.h>
#include <linux/videodev2.h>
#include <poll.h>
#include <sys/epoll.h>
#include <sys/ioctl.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstring>

#include "fd.h"
#include "hal/convert.h"
#include "hal/devices.h"

namespace hal {

namespace {

int xioctl(int fd, unsigned long request, void* arg) {
  int r;
  do r = ioctl(fd, request, arg);
  while (r == -1 && errno == EINTR);
  return r;
}

struct Unmap {
  std::size_t length = 0;
  void operator()(void* p) const { munmap(p, length); }
};
using Mapping = std::unique_ptr<void, Unmap>;

std::uint32_t fourcc(PixelFormat f) {
  switch (f) {
    case PixelFormat::Mjpeg: return V4L2_PIX_FMT_MJPEG;
    case PixelFormat::Yuyv: return V4L2_PIX_FMT_YUYV;
    case PixelFormat::Rgb24: return V4L2_PIX_FMT_RGB24;
    case PixelFormat::Auto: return 0;
  }
  return 0;
}

std::string fourcc_text(std::uint32_t f) {
  return {static_cast<char>(f & 0xff), static_cast<char>((f >> 8) & 0xff), static_cast<char>((f >> 16) & 0xff),
          static_cast<char>((f >> 24) & 0xff)};
}

class V4l2Camera final : public Camera {
public:
  explicit V4l2Camera(const CameraConfig& config)
      : config_(config), epoll_(detail::make_epoll()), reopen_timer_(detail::make_timer()) {
    detail::epoll_watch(epoll_.get(), reopen_timer_.get());
    if (!open_device()) lose();
  }
  ~V4l2Camera() override { teardown(); }

  int fd() const override { return epoll_.get(); }
  CameraState state() const override { return state_; }
  const std::string& last_error() const override { return error_; }

  void service() override {
    if (state_ != CameraState::Lost) return;
    std::uint64_t expirations = 0;
    if (::read(reopen_timer_.get(), &expirations, sizeof expirations) != sizeof expirations) return;  // not due
    if (open_device()) {
      detail::arm_timer(reopen_timer_.get(), Nanos::max());
      error_.clear();
    } else {
      lose();
    }
  }

  bool read_frame(RgbImage& out) override {
    if (state_ != CameraState::Streaming) return false;
    v4l2_buffer buf{};
    buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    buf.memory = V4L2_MEMORY_MMAP;
    if (xioctl(dev_.get(), VIDIOC_DQBUF, &buf) != 0) {
      if (errno == EAGAIN) return false;
      fail("VIDIOC_DQBUF", errno);
      return false;
    }
    bool ok = (buf.flags & V4L2_BUF_FLAG_ERROR) == 0 && buf.index < buffers_.size();
    if (ok) {
      const auto* data = static_cast<const std::uint8_t*>(buffers_[buf.index].get());
      const std::span<const std::uint8_t> bytes(data, buf.bytesused);
      out.resize(width_, height_);
      switch (pixfmt_) {
        case V4L2_PIX_FMT_YUYV:
          ok = bytes.size() >= static_cast<std::size_t>(stride_) * height_;
          if (ok) yuyv_to_rgb(bytes, width_, height_, stride_, out);
          break;
        case V4L2_PIX_FMT_RGB24:
          ok = bytes.size() >= static_cast<std::size_t>(stride_) * height_;
          for (int y = 0; ok && y < height_; ++y)
            std::memcpy(out.at(0, y), data + static_cast<std::size_t>(y) * stride_, static_cast<std::size_t>(width_) * 3);
          break;
        default:  // MJPEG; a corrupt frame is skipped, the next one is usually fine
          ok = mjpeg_.decode(bytes, out, nullptr);
          break;
      }
    }
    if (xioctl(dev_.get(), VIDIOC_QBUF, &buf) != 0) {
      fail("VIDIOC_QBUF", errno);
      return false;
    }
    return ok;
  }

private:
  bool open_device() {
    const std::string& path = config_.device;
    dev_.reset(::open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC));
    if (!dev_) return set_error(path + ": cannot open camera: " + detail::errno_text(errno));

    v4l2_capability cap{};
    if (xioctl(dev_.get(), VIDIOC_QUERYCAP, &cap) != 0)
      return set_error(path + ": VIDIOC_QUERYCAP failed (not a V4L2 device?): " + detail::errno_text(errno));
    const std::uint32_t caps = (cap.capabilities & V4L2_CAP_DEVICE_CAPS) ? cap.device_caps : cap.capabilities;
    if (!(caps & V4L2_CAP_VIDEO_CAPTURE))
      return set_error(path + ": capabilities: expected VIDEO_CAPTURE (a metadata or output node was given?)");
    if (!(caps & V4L2_CAP_STREAMING)) return set_error(path + ": capabilities: expected STREAMING (mmap I/O)");

    const PixelFormat order[] = {config_.format == PixelFormat::Auto ? PixelFormat::Mjpeg : config_.format,
                                 config_.format == PixelFormat::Auto ? PixelFormat::Yuyv : config_.format};
    v4l2_format fmt{};
    bool accepted = false;
    for (PixelFormat want : order) {
      fmt = {};
      fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      fmt.fmt.pix.width = static_cast<std::uint32_t>(config_.width);
      fmt.fmt.pix.height = static_cast<std::uint32_t>(config_.height);
      fmt.fmt.pix.pixelformat = fourcc(want);
      fmt.fmt.pix.field = V4L2_FIELD_NONE;
      if (xioctl(dev_.get(), VIDIOC_S_FMT, &fmt) != 0)
        return set_error(path + ": VIDIOC_S_FMT: " + detail::errno_text(errno));
      // Drivers substitute what they support; only take a format we can convert.
      if (fmt.fmt.pix.pixelformat == fourcc(want)) {
        accepted = true;
        break;
      }
    }
    if (!accepted)
      return set_error(path + ": pixel format: expected " + std::string(to_string(config_.format)) +
                       " (MJPEG, YUYV or RGB24), driver offers " + fourcc_text(fmt.fmt.pix.pixelformat));
    pixfmt_ = fmt.fmt.pix.pixelformat;
    width_ = static_cast<int>(fmt.fmt.pix.width);
    height_ = static_cast<int>(fmt.fmt.pix.height);
    const int min_stride = pixfmt_ == V4L2_PIX_FMT_RGB24 ? width_ * 3 : width_ * 2;
    stride_ = std::max(static_cast<int>(fmt.fmt.pix.bytesperline), min_stride);

    v4l2_requestbuffers req{};
    req.count = static_cast<std::uint32_t>(config_.buffers);
    req.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    req.memory = V4L2_MEMORY_MMAP;
    if (xioctl(dev_.get(), VIDIOC_REQBUFS, &req) != 0 || req.count < 2)
      return set_error(path + ": VIDIOC_REQBUFS: expected at least 2 mmap buffers: " + detail::errno_text(errno));
    for (std::uint32_t i = 0; i < req.count; ++i) {
      v4l2_buffer buf{};
      buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      buf.memory = V4L2_MEMORY_MMAP;
      buf.index = i;
      if (xioctl(dev_.get(), VIDIOC_QUERYBUF, &buf) != 0)
        return set_error(path + ": VIDIOC_QUERYBUF " + std::to_string(i) + ": " + detail::errno_text(errno));
      void* p = mmap(nullptr, buf.length, PROT_READ | PROT_WRITE, MAP_SHARED, dev_.get(), buf.m.offset);
      if (p == MAP_FAILED) return set_error(path + ": mmap buffer " + std::to_string(i) + ": " + detail::errno_text(errno));
      buffers_.emplace_back(p, Unmap{buf.length});
      if (xioctl(dev_.get(), VIDIOC_QBUF, &buf) != 0)
        return set_error(path + ": VIDIOC_QBUF " + std::to_string(i) + ": " + detail::errno_text(errno));
    }
    v4l2_buf_type type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (xioctl(dev_.get(), VIDIOC_STREAMON, &type) != 0)
      return set_error(path + ": VIDIOC_STREAMON: " + detail::errno_text(errno));
    streaming_ = true;
    detail::epoll_watch(epoll_.get(), dev_.get());
    state_ = CameraState::Streaming;
    return true;
  }

  bool set_error(std::string message) {
    error_ = std::move(message);
    teardown();
    return false;
  }

  // ENODEV (unplugged) and other stream errors: drop everything and retry later; never wait on it.
  void fail(const char* what, int err) {
    error_ = config_.device + ": " + what + ": " + detail::errno_text(err) +
             (err == ENODEV ? " (camera unplugged?); retrying" : "");
    lose();
  }

  void lose() {
    teardown();
    state_ = CameraState::Lost;
    detail::arm_timer(reopen_timer_.get(), MonotonicClock().now() + config_.reopen_interval);
  }

  void teardown() {
    if (dev_) {
      if (streaming_) {
        v4l2_buf_type type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
        xioctl(dev_.get(), VIDIOC_STREAMOFF, &type);
      }
      epoll_ctl(epoll_.get(), EPOLL_CTL_DEL, dev_.get(), nullptr);
    }
    streaming_ = false;
    buffers_.clear();  // unmapped before the fd closes, then the driver frees them with the fd
    dev_.reset();
    state_ = CameraState::Closed;
  }

  CameraConfig config_;
  UniqueFd epoll_;
  UniqueFd reopen_timer_;
  UniqueFd dev_;
  std::vector<Mapping> buffers_;
  bool streaming_ = false;
  std::uint32_t pixfmt_ = 0;
  int width_ = 0, height_ = 0, stride_ = 0;
  MjpegDecoder mjpeg_;
  CameraState state_ = CameraState::Closed;
  std::string error_;
};

}  // namespace

std::unique_ptr<Camera> open_v4l2_camera(const CameraConfig& config) { return std::make_unique<V4l2Camera>(config); }

}  // namespace hal
