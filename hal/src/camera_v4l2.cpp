#include <fcntl.h>
#include <linux/videodev2.h>
#include <poll.h>
#include <sys/epoll.h>
#include <sys/ioctl.h>
#include <sys/mman.h>

#include <cerrno>
#include <cstring>

#include "base/errno_text.h"
#include "camera_schedule.h"
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
    case PixelFormat::mjpeg:
      return V4L2_PIX_FMT_MJPEG;
    case PixelFormat::yuyv:
      return V4L2_PIX_FMT_YUYV;
    case PixelFormat::rgb24:
      return V4L2_PIX_FMT_RGB24;
    case PixelFormat::automatic:
      return 0;
  }
  return 0;
}

std::string fourcc_text(std::uint32_t f) {
  return {static_cast<char>(f & 0xff), static_cast<char>((f >> 8) & 0xff), static_cast<char>((f >> 16) & 0xff),
          static_cast<char>((f >> 24) & 0xff)};
}

class V4l2Camera final : public Camera {
 public:
  V4l2Camera(const CameraConfig& config, const Clock& clock)
      : config_(config),
        clock_(clock),
        schedule_(config.reopen_interval, config.frame_timeout),
        epoll_(detail::make_epoll()),
        timer_(detail::make_timer()) {
    // One timer for both deadlines: the reopen while lost, the no-frame check while streaming.
    detail::epoll_watch(epoll_.get(), timer_.get());
    if (open_device())
      schedule_.opened(clock_.now());
    else
      lose();
    arm();
  }
  ~V4l2Camera() override { teardown(); }

  int fd() const override { return epoll_.get(); }
  CameraState state() const override { return state_; }
  const std::string& last_error() const override { return error_; }

  void service() override {
    // The decisions read the clock, not the timer, so a manual clock drives them; the timer only
    // wakes the loop and is re-armed from the schedule every time.
    detail::drain(timer_.get());
    const Nanos now = clock_.now();
    if (state_ == CameraState::streaming && schedule_.stalled(now)) {
      const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now - schedule_.last_frame()).count();
      error_ = config_.device + ": no usable frame for " + std::to_string(ms) +
               " ms (camera.frame_timeout_ms = " + std::to_string(config_.frame_timeout.count()) + ")" +
               (error_.empty() ? "" : "; last error: " + error_) + "; reopening";
      lose();
    } else if (state_ == CameraState::lost && schedule_.reopen_due(now)) {
      if (open_device()) {
        error_.clear();
        schedule_.opened(now);
      } else {
        lose();
      }
    }
    arm();
  }

  bool read_frame(RgbImage& out) override {
    if (state_ != CameraState::streaming) return false;
    v4l2_buffer buf{};
    buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    buf.memory = V4L2_MEMORY_MMAP;
    if (xioctl(dev_.get(), VIDIOC_DQBUF, &buf) != 0) {
      if (errno == EAGAIN) return false;
      fail("VIDIOC_DQBUF", errno);
      return false;
    }
    // A bad frame is skipped (the next one is usually fine) but kept as the last error. Built only on
    // failure: the frame path does not allocate.
    auto frame_error = [&](const std::string& what) {
      error_ = config_.device + ": frame " + std::to_string(buf.sequence) + ": " + what;
    };
    bool ok = false;
    if (buf.flags & V4L2_BUF_FLAG_ERROR)
      frame_error("the driver flagged it as corrupt");
    else if (buf.index >= buffers_.size())
      frame_error("buffer index " + std::to_string(buf.index) + " out of range");
    else
      ok = true;
    if (ok) {
      const auto* data = static_cast<const std::uint8_t*>(buffers_[buf.index].get());
      const std::span<const std::uint8_t> bytes(data, buf.bytesused);
      out.resize(width_, height_);
      const std::size_t expected = static_cast<std::size_t>(stride_) * height_;
      switch (pixfmt_) {
        case V4L2_PIX_FMT_YUYV:
        case V4L2_PIX_FMT_RGB24:
          ok = bytes.size() >= expected;
          if (!ok) {
            frame_error("expected at least " + std::to_string(expected) + " bytes, got " + std::to_string(bytes.size()));
          } else if (pixfmt_ == V4L2_PIX_FMT_YUYV) {
            yuyv_to_rgb(bytes, width_, height_, stride_, out);
          } else {
            const auto row = static_cast<std::size_t>(width_) * 3;
            for (int y = 0; y < height_; ++y) std::memcpy(out.at(0, y), data + static_cast<std::size_t>(y) * stride_, row);
          }
          break;
        default: {          // MJPEG
          std::string why;  // written only on failure
          ok = mjpeg_.decode(bytes, out, &why);
          if (!ok) frame_error(why);
          break;
        }
      }
    }
    if (xioctl(dev_.get(), VIDIOC_QBUF, &buf) != 0) {
      fail("VIDIOC_QBUF", errno);
      return false;
    }
    // Only a usable frame proves the stream alive: a camera sending nothing but corrupt frames is
    // reopened like a silent one.
    if (ok) schedule_.frame(clock_.now());
    return ok;
  }

 private:
  bool open_device() {
    const std::string& path = config_.device;
    dev_.reset(::open(path.c_str(), O_RDWR | O_NONBLOCK | O_CLOEXEC));
    if (!dev_) return set_error(path + ": cannot open camera: " + base::errno_text(errno));

    v4l2_capability cap{};
    if (xioctl(dev_.get(), VIDIOC_QUERYCAP, &cap) != 0)
      return set_error(path + ": VIDIOC_QUERYCAP failed (not a V4L2 device?): " + base::errno_text(errno));
    const std::uint32_t caps = (cap.capabilities & V4L2_CAP_DEVICE_CAPS) ? cap.device_caps : cap.capabilities;
    if (!(caps & V4L2_CAP_VIDEO_CAPTURE))
      return set_error(path + ": capabilities: expected VIDEO_CAPTURE (a metadata or output node was given?)");
    if (!(caps & V4L2_CAP_STREAMING)) return set_error(path + ": capabilities: expected STREAMING (mmap I/O)");

    const PixelFormat order[] = {config_.format == PixelFormat::automatic ? PixelFormat::mjpeg : config_.format,
                                 config_.format == PixelFormat::automatic ? PixelFormat::yuyv : config_.format};
    v4l2_format fmt{};
    bool accepted = false;
    for (PixelFormat want : order) {
      fmt = {};
      fmt.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      fmt.fmt.pix.width = static_cast<std::uint32_t>(config_.width);
      fmt.fmt.pix.height = static_cast<std::uint32_t>(config_.height);
      fmt.fmt.pix.pixelformat = fourcc(want);
      fmt.fmt.pix.field = V4L2_FIELD_NONE;
      if (xioctl(dev_.get(), VIDIOC_S_FMT, &fmt) != 0) return set_error(path + ": VIDIOC_S_FMT: " + base::errno_text(errno));
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
    if (xioctl(dev_.get(), VIDIOC_REQBUFS, &req) != 0)
      return set_error(path + ": VIDIOC_REQBUFS (" + std::to_string(config_.buffers) +
                       " mmap buffers): " + base::errno_text(errno));
    if (req.count < 2)
      return set_error(path + ": VIDIOC_REQBUFS: expected at least 2 mmap buffers, the driver granted " +
                       std::to_string(req.count));
    for (std::uint32_t i = 0; i < req.count; ++i) {
      v4l2_buffer buf{};
      buf.type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
      buf.memory = V4L2_MEMORY_MMAP;
      buf.index = i;
      if (xioctl(dev_.get(), VIDIOC_QUERYBUF, &buf) != 0)
        return set_error(path + ": VIDIOC_QUERYBUF " + std::to_string(i) + ": " + base::errno_text(errno));
      void* p = mmap(nullptr, buf.length, PROT_READ | PROT_WRITE, MAP_SHARED, dev_.get(), buf.m.offset);
      if (p == MAP_FAILED) return set_error(path + ": mmap buffer " + std::to_string(i) + ": " + base::errno_text(errno));
      buffers_.emplace_back(p, Unmap{buf.length});
      if (xioctl(dev_.get(), VIDIOC_QBUF, &buf) != 0)
        return set_error(path + ": VIDIOC_QBUF " + std::to_string(i) + ": " + base::errno_text(errno));
    }
    v4l2_buf_type type = V4L2_BUF_TYPE_VIDEO_CAPTURE;
    if (xioctl(dev_.get(), VIDIOC_STREAMON, &type) != 0) return set_error(path + ": VIDIOC_STREAMON: " + base::errno_text(errno));
    streaming_ = true;
    detail::epoll_watch(epoll_.get(), dev_.get());
    state_ = CameraState::streaming;
    return true;
  }

  bool set_error(std::string message) {
    error_ = std::move(message);
    teardown();
    return false;
  }

  // ENODEV (unplugged) and other stream errors: drop everything and retry later; never wait on it.
  void fail(const char* what, int err) {
    error_ =
        config_.device + ": " + what + ": " + base::errno_text(err) + (err == ENODEV ? " (camera unplugged?); retrying" : "");
    lose();
  }

  void lose() {
    teardown();
    state_ = CameraState::lost;
    schedule_.lost(clock_.now());
    arm();
  }

  void arm() { detail::arm_timer(timer_.get(), schedule_.deadline()); }

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
    state_ = CameraState::closed;
  }

  CameraConfig config_;
  const Clock& clock_;
  detail::CameraSchedule schedule_;
  base::UniqueFd epoll_;
  base::UniqueFd timer_;
  base::UniqueFd dev_;
  std::vector<Mapping> buffers_;
  bool streaming_ = false;
  std::uint32_t pixfmt_ = 0;
  int width_ = 0, height_ = 0, stride_ = 0;
  MjpegDecoder mjpeg_;
  CameraState state_ = CameraState::closed;
  std::string error_;
};

}  // namespace

std::unique_ptr<Camera> open_v4l2_camera(const CameraConfig& config, const Clock& clock) {
  return std::make_unique<V4l2Camera>(config, clock);
}

}  // namespace hal
