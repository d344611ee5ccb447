#include <poll.h>

#include <algorithm>
#include <cmath>

#include "base/names.h"
#include "fd.h"
#include "hal/board.h"
#include "hal/mock.h"
#include "homography.h"

namespace hal {

namespace {
constexpr base::Name<CameraState> kCameraStateNames[] = {
    {CameraState::closed, "closed"}, {CameraState::streaming, "streaming"}, {CameraState::lost, "lost"}};
static_assert(base::in_enum_order(kCameraStateNames));
constexpr base::Name<PixelFormat> kPixelFormatNames[] = {
    {PixelFormat::automatic, "auto"}, {PixelFormat::mjpeg, "mjpeg"}, {PixelFormat::yuyv, "yuyv"}, {PixelFormat::rgb24, "rgb24"}};
static_assert(base::in_enum_order(kPixelFormatNames));
}  // namespace

std::string_view to_string(CameraState s) {
  return base::name_of(kCameraStateNames, s);
}
std::string_view to_string(PixelFormat f) {
  return base::name_of(kPixelFormatNames, f);
}
bool parse_pixel_format(std::string_view text, PixelFormat& out) {
  return base::parse_name(kPixelFormatNames, text, out);
}
std::string pixel_format_names() {
  return base::names_text(kPixelFormatNames);
}

bool Camera::capture(RgbImage& out, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    if (read_frame(out)) return true;
    service();
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd p{fd(), POLLIN, 0};
    poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 100)));
  }
}

std::array<double, 9> homography_for_corners(int display_w, int display_h, const std::array<std::array<double, 2>, 4>& corners) {
  // Pixel centres at integers, so the screen's outer edges are at -0.5 and size - 0.5.
  const double l = -0.5, t = -0.5, r = display_w - 0.5, b = display_h - 0.5;
  const detail::Point src[4] = {{l, t}, {r, t}, {r, b}, {l, b}};
  detail::Point dst[4];
  for (int i = 0; i < 4; ++i) dst[i] = {corners[i][0], corners[i][1]};
  detail::Mat3 h{1, 0, 0, 0, 1, 0, 0, 0, 1};
  if (!detail::fit_homography(src, dst, h)) throw ConfigError("camera model: the four screen corners are degenerate");
  return h;
}

namespace {

// Deterministic across standard libraries, unlike std::normal_distribution.
struct Rng {
  std::uint64_t state;
  double uniform() {
    state ^= state << 13;
    state ^= state >> 7;
    state ^= state << 17;
    return (static_cast<double>(state >> 11) + 0.5) * (1.0 / 9007199254740992.0);
  }
  double normal() { return std::sqrt(-2.0 * std::log(uniform())) * std::cos(6.283185307179586 * uniform()); }
};

void gaussian_blur(std::vector<float>& img, int w, int h, double sigma) {
  const int radius = static_cast<int>(std::ceil(3 * sigma));
  std::vector<float> k(static_cast<std::size_t>(2 * radius + 1));
  float sum = 0;
  for (int i = -radius; i <= radius; ++i) sum += k[i + radius] = static_cast<float>(std::exp(-0.5 * i * i / (sigma * sigma)));
  for (float& v : k) v /= sum;
  std::vector<float> tmp(img.size());
  for (int pass = 0; pass < 2; ++pass) {
    const bool horizontal = pass == 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 3; ++c) {
          float acc = 0;
          for (int i = -radius; i <= radius; ++i) {
            const int sx = horizontal ? std::clamp(x + i, 0, w - 1) : x;
            const int sy = horizontal ? y : std::clamp(y + i, 0, h - 1);
            acc += k[i + radius] * img[(static_cast<std::size_t>(sy) * w + sx) * 3 + c];
          }
          tmp[(static_cast<std::size_t>(y) * w + x) * 3 + c] = acc;
        }
    img.swap(tmp);
  }
}

}  // namespace

void synthesize_capture(const RgbImage& displayed, const CameraModel& m, std::uint32_t noise_frame, RgbImage& out) {
  out.resize(m.width, m.height);
  const detail::Mat3 h =
      m.screen_corners ? homography_for_corners(displayed.width, displayed.height, *m.screen_corners) : m.homography;
  detail::Mat3 inv;
  if (!detail::invert(h, inv)) inv = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  std::vector<float> img(static_cast<std::size_t>(m.width) * m.height * 3);
  // 2x2 supersampling per camera pixel stands in for the sensor's pixel area.
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) {
      float acc[3] = {0, 0, 0};
      for (int s = 0; s < 4; ++s) {
        const detail::Point p = detail::apply(inv, x - 0.25 + 0.5 * (s % 2), y - 0.25 + 0.5 * (s / 2));
        const int dx = static_cast<int>(std::lround(p.x)), dy = static_cast<int>(std::lround(p.y));
        const bool inside = dx >= 0 && dy >= 0 && dx < displayed.width && dy < displayed.height;
        for (int c = 0; c < 3; ++c) acc[c] += inside ? displayed.at(dx, dy)[c] : m.surround;
      }
      for (int c = 0; c < 3; ++c) img[(static_cast<std::size_t>(y) * m.width + x) * 3 + c] = acc[c] / 4.0f;
    }
  if (m.blur_sigma > 0) gaussian_blur(img, m.width, m.height, m.blur_sigma);
  Rng rng{0x9E3779B97F4A7C15ull ^ (static_cast<std::uint64_t>(m.seed) << 32) ^ noise_frame};
  const double cx = (m.width - 1) / 2.0, cy = (m.height - 1) / 2.0, r2max = cx * cx + cy * cy;
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) {
      const double r2 = ((x - cx) * (x - cx) + (y - cy) * (y - cy)) / r2max;
      const double vignette = 1.0 - m.vignetting * r2;
      for (int c = 0; c < 3; ++c) {
        const double lin = m.exposure * vignette * img[(static_cast<std::size_t>(y) * m.width + x) * 3 + c] / 255.0;
        double v = 255.0 * std::pow(std::clamp(lin, 0.0, 1.0), 1.0 / m.gamma);
        if (m.noise_sigma > 0) v += m.noise_sigma * rng.normal();
        out.at(x, y)[c] = static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
      }
    }
}

RgbImage make_test_scene(int width, int height, int scene, double t) {
  RgbImage img(width, height);
  Rng rng{0xC0FFEEull + static_cast<std::uint64_t>(scene) * 7919};
  const double horizon = height * (0.45 + 0.15 * rng.uniform());
  const double sky[3] = {90 + 80 * rng.uniform(), 120 + 80 * rng.uniform(), 200 + 50 * rng.uniform()};
  const double ground[3] = {60 + 120 * rng.uniform(), 50 + 100 * rng.uniform(), 40 + 60 * rng.uniform()};
  struct Ball {
    double x, y, r, vx, col[3];
    bool box;
  };
  Ball balls[6];
  for (Ball& b : balls) {
    b.x = width * (0.1 + 0.8 * rng.uniform());
    b.y = horizon + (height - horizon) * (0.1 + 0.6 * rng.uniform());
    b.r = std::min(width, height) * (0.06 + 0.1 * rng.uniform());
    b.vx = width * (0.05 + 0.1 * rng.uniform()) * (rng.uniform() < 0.5 ? -1 : 1);
    for (double& c : b.col) c = 40 + 200 * rng.uniform();
    b.box = rng.uniform() < 0.4;
  }
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double c[3];
      if (y < horizon) {
        const double k = 0.6 + 0.4 * y / horizon;
        for (int i = 0; i < 3; ++i) c[i] = sky[i] * k;
      } else {
        // A checker floor in perspective: the texture that makes shifts and scaling visible.
        const double depth = (height - horizon) / (y - horizon + 1.0);
        // The floor scrolls with t as under a moving camera path.
        const double pan = t * width * 0.1;
        const bool check =
            (static_cast<int>(std::floor((x - width / 2.0 + pan) * depth / 40.0)) + static_cast<int>(std::floor(depth * 4.0))) %
                2 ==
            0;
        for (int i = 0; i < 3; ++i) c[i] = ground[i] * (check ? 1.0 : 0.6);
      }
      for (const Ball& b : balls) {
        const double bx = b.x + b.vx * t;
        const double dx = (x - bx) / b.r, dy = (y - b.y) / b.r;
        if (b.box ? (std::abs(dx) < 0.8 && std::abs(dy) < 0.8) : (dx * dx + dy * dy < 1)) {
          // Lambert shading from the upper left, with a rim darkening that looks like ambient occlusion.
          const double nz = b.box ? 0.8 : std::sqrt(std::max(0.0, 1 - dx * dx - dy * dy));
          const double shade =
              b.box ? (dx < dy ? 0.9 : 0.6) : std::clamp(0.25 + 0.75 * (-0.5 * dx - 0.5 * dy + 0.7 * nz), 0.1, 1.0);
          for (int i = 0; i < 3; ++i) c[i] = b.col[i] * shade;
        }
      }
      for (int i = 0; i < 3; ++i) img.at(x, y)[i] = static_cast<std::uint8_t>(std::clamp(c[i], 0.0, 255.0));
    }
  return img;
}

MockCamera::MockCamera(const std::vector<std::string>& image_files, const Clock& clock, Nanos frame_interval)
    : clock_(clock), interval_(frame_interval), timer_(detail::make_timer()) {
  for (const auto& f : image_files) {
    RgbImage img;
    std::string err;
    if (!load_image(f, img, &err)) throw ConfigError("mock camera: " + err);
    files_.push_back(std::move(img));
  }
  if (files_.empty()) throw ConfigError("mock camera: expected at least one image file");
  arm(next_frame_ = clock_.now());
}

MockCamera::MockCamera(CameraModel model, const Clock& clock, Nanos frame_interval)
    : model_(model), synthetic_(true), clock_(clock), interval_(frame_interval), timer_(detail::make_timer()) {}

void MockCamera::arm(Nanos at) {
  detail::arm_timer(timer_.get(), at);
}

void MockCamera::show(const RgbImage& displayed) {
  const bool first = displayed_.empty();
  displayed_ = displayed;
  // Until now there was nothing to film and the timer was idle; from now on frames come.
  if (first && state_ == CameraState::streaming) arm(next_frame_ = std::max(next_frame_, clock_.now()));
}

void MockCamera::unplug() {
  plugged_ = false;
  state_ = CameraState::lost;
  error_ = "mock camera: No such device (unplugged)";
  arm(clock_.now());  // wake the loop once, so it sees the state; read_frame()/service() disarm it
}

void MockCamera::replug() {
  plugged_ = true;
  arm(clock_.now());  // a reopen is due: service() brings it back
}

int MockCamera::fd() const {
  return timer_.get();
}

void MockCamera::service() {
  if (state_ != CameraState::lost) return;
  detail::drain(timer_.get());
  if (!plugged_) {
    arm(Nanos::max());  // nothing to retry until replug()
    return;
  }
  state_ = CameraState::streaming;
  error_.clear();
  next_frame_ = clock_.now();
  arm(has_source() ? next_frame_ : Nanos::max());
}

bool MockCamera::read_frame(RgbImage& out) {
  if (state_ != CameraState::streaming) return false;
  // Draining before the check keeps fd() readable only while a frame is due: no spinning loop.
  detail::drain(timer_.get());
  const Nanos now = clock_.now();
  if (!has_source()) {
    arm(Nanos::max());
    return false;
  }
  if (now < next_frame_) {
    arm(next_frame_);
    return false;
  }
  // Frames the app did not read in time are gone, as with a camera's ring of buffers.
  next_frame_ += interval_;
  if (next_frame_ <= now) next_frame_ = now + interval_;
  arm(next_frame_);
  if (synthetic_) {
    synthesize_capture(displayed_, model_, frame_++, out);
    return true;
  }
  const RgbImage& src = files_[next_file_];
  next_file_ = (next_file_ + 1) % files_.size();
  out.resize(src.width, src.height);
  std::copy(src.pixels.begin(), src.pixels.end(), out.pixels.begin());
  return true;
}

}  // namespace hal
