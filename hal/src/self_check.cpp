#include "hal/self_check.h"

#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <vector>

#include "homography.h"

namespace hal {

namespace {

constexpr int kMarkerCells = 10;  // tag36h11 with its one-cell white border
constexpr int kBorderCells = 8;   // the black square the detector reports corners of
constexpr int kIdGroups = 587 / 4;
const char* const kCornerNames[4] = {"top-left", "top-right", "bottom-right", "bottom-left"};

using FamilyPtr = std::unique_ptr<apriltag_family_t, decltype(&tag36h11_destroy)>;
using DetectorPtr = std::unique_ptr<apriltag_detector_t, decltype(&apriltag_detector_destroy)>;
using DetectionsPtr = std::unique_ptr<zarray_t, decltype(&apriltag_detections_destroy)>;
// Debian's libapriltag does not export image_u8_destroy; this is what it does (common/image_u8.c):
// the struct and its pixel buffer are separate malloc blocks.
struct TagImageFree {
  void operator()(image_u8_t* im) const {
    std::free(im->buf);
    std::free(im);
  }
};
using TagImagePtr = std::unique_ptr<image_u8_t, TagImageFree>;

float luma(const std::uint8_t* p) {
  return 0.299f * p[0] + 0.587f * p[1] + 0.114f * p[2];
}

}  // namespace

FiducialLayout FiducialLayout::for_display(int width, int height, std::uint32_t sequence) {
  FiducialLayout l;
  l.display_width = width;
  l.display_height = height;
  l.cell = std::max(2, std::min(width, height) / (6 * kMarkerCells));
  l.first_id = static_cast<int>(4 * (sequence % kIdGroups));
  return l;
}

std::array<int, 2> FiducialLayout::marker_origin(int corner) const {
  const int s = marker_size();
  switch (corner) {
    case 0:
      return {0, 0};
    case 1:
      return {display_width - s, 0};
    case 2:
      return {display_width - s, display_height - s};
    default:
      return {0, display_height - s};
  }
}

void draw_fiducials(RgbImage& frame, const FiducialLayout& layout) {
  FamilyPtr family(tag36h11_create(), &tag36h11_destroy);
  for (int corner = 0; corner < 4; ++corner) {
    TagImagePtr tag(apriltag_to_image(family.get(), layout.first_id + corner));
    const auto [ox, oy] = layout.marker_origin(corner);
    for (int y = 0; y < layout.marker_size(); ++y)
      for (int x = 0; x < layout.marker_size(); ++x) {
        const std::uint8_t v = tag->buf[(y / layout.cell) * tag->stride + x / layout.cell];
        std::uint8_t* p = frame.at(ox + x, oy + y);
        p[0] = p[1] = p[2] = v;
      }
  }
}

struct DisplayChecker::Impl {
  SelfCheckOptions options;
  FamilyPtr family{tag36h11_create(), &tag36h11_destroy};
  DetectorPtr detector{apriltag_detector_create(), &apriltag_detector_destroy};
  std::vector<std::uint8_t> grey;
  std::vector<float> capture_luma, ref, cap;
  std::vector<std::uint8_t> valid;
  RgbImage warped;

  explicit Impl(SelfCheckOptions o) : options(o) {
    apriltag_detector_add_family(detector.get(), family.get());
    detector->nthreads = 1;
    detector->quad_sigma = 0.0f;
    detector->refine_edges = true;
  }

  float sample(int w, int h, double x, double y) const {
    x = std::clamp(x, 0.0, w - 1.0);
    y = std::clamp(y, 0.0, h - 1.0);
    const int x0 = std::min(static_cast<int>(x), w - 2), y0 = std::min(static_cast<int>(y), h - 2);
    const float fx = static_cast<float>(x - x0), fy = static_cast<float>(y - y0);
    const float* r0 = &capture_luma[static_cast<std::size_t>(y0) * w + x0];
    const float* r1 = r0 + w;
    return (r0[0] * (1 - fx) + r0[1] * fx) * (1 - fy) + (r1[0] * (1 - fx) + r1[1] * fx) * fy;
  }
};

DisplayChecker::DisplayChecker(SelfCheckOptions options) : impl_(std::make_unique<Impl>(options)) {}
DisplayChecker::~DisplayChecker() = default;
const RgbImage& DisplayChecker::last_warped() const {
  return impl_->warped;
}

SelfCheckResult DisplayChecker::check(const RgbImage& presented, const FiducialLayout& layout, const RgbImage& capture) {
  Impl& m = *impl_;
  SelfCheckResult result;
  if (presented.width != layout.display_width || presented.height != layout.display_height || capture.width < 2 ||
      capture.height < 2) {
    result.reason = "presented frame is " + std::to_string(presented.width) + "x" + std::to_string(presented.height) +
                    ", expected the layout's " + std::to_string(layout.display_width) + "x" +
                    std::to_string(layout.display_height) + " and a capture of at least 2x2";
    return result;
  }

  // 1. Find the four markers of this check.
  const int cw = capture.width, ch = capture.height;
  m.grey.resize(static_cast<std::size_t>(cw) * ch);
  m.capture_luma.resize(m.grey.size());
  for (std::size_t i = 0; i < m.grey.size(); ++i) {
    m.capture_luma[i] = luma(&capture.pixels[i * 3]);
    m.grey[i] = static_cast<std::uint8_t>(std::lround(m.capture_luma[i]));
  }
  // Large captures are searched at half resolution: markers stay big enough and detection is 4x cheaper.
  m.detector->quad_decimate = cw > 1000 ? 2.0f : 1.0f;
  image_u8_t im{cw, ch, cw, m.grey.data()};
  DetectionsPtr detections(apriltag_detector_detect(m.detector.get(), &im), &apriltag_detections_destroy);

  std::array<bool, 4> seen{};
  std::array<std::array<detail::Point, 4>, 4> corners{};
  int foreign_id = -1;
  for (int i = 0; i < zarray_size(detections.get()); ++i) {
    apriltag_detection_t* det = nullptr;
    zarray_get(detections.get(), i, &det);
    if (det->hamming > 1) continue;
    const int k = det->id - layout.first_id;
    if (k < 0 || k > 3) {
      foreign_id = det->id;
      continue;
    }
    seen[k] = true;
    // The detector puts pixel edges at integers; hal puts pixel centres there.
    for (int c = 0; c < 4; ++c) corners[k][c] = {det->p[c][0] - 0.5, det->p[c][1] - 0.5};
  }
  result.markers_found = static_cast<int>(std::count(seen.begin(), seen.end(), true));
  if (result.markers_found < 4) {
    if (foreign_id >= 0) {
      result.reason = "saw marker id " + std::to_string(foreign_id) + " from another check, expected ids " +
                      std::to_string(layout.first_id) + ".." + std::to_string(layout.first_id + 3) + " (frozen or stale frame)";
    } else {
      const int missing = static_cast<int>(std::find(seen.begin(), seen.end(), false) - seen.begin());
      result.reason = std::string(kCornerNames[missing]) + " marker (id " + std::to_string(layout.first_id + missing) +
                      ") not found (screen dark, picture shifted or cropped, or camera misaimed)";
    }
    return result;
  }

  // 2. Display -> camera homography from the 16 border corners. Detector corner order for an
  // upright tag: bottom-left, bottom-right, top-right, top-left (image y down).
  std::array<detail::Point, 16> src{}, dst{};
  for (int k = 0; k < 4; ++k) {
    const auto [ox, oy] = layout.marker_origin(k);
    const double l = ox + layout.cell - 0.5, t = oy + layout.cell - 0.5;
    const double r = l + kBorderCells * layout.cell, b = t + kBorderCells * layout.cell;
    const detail::Point display[4] = {{l, b}, {r, b}, {r, t}, {l, t}};
    for (int c = 0; c < 4; ++c) {
      src[k * 4 + c] = display[c];
      dst[k * 4 + c] = corners[k][c];
    }
  }
  detail::Mat3 h;
  if (!detail::fit_homography(src, dst, h)) {
    result.reason = "markers found but their corners are degenerate (no homography)";
    return result;
  }
  double err2 = 0;
  for (std::size_t i = 0; i < src.size(); ++i) {
    const detail::Point p = detail::apply(h, src[i].x, src[i].y);
    err2 += (p.x - dst[i].x) * (p.x - dst[i].x) + (p.y - dst[i].y) * (p.y - dst[i].y);
  }
  const double rms = std::sqrt(err2 / static_cast<double>(src.size()));
  // A flat screen maps by one homography; markers that disagree by more than a few camera pixels
  // were moved relative to each other (a scaled or partly shifted picture).
  if (rms > 3.0) {
    result.reason =
        "markers do not lie on one plane as laid out (reprojection error " + std::to_string(rms) + " px, expected at most 3)";
    return result;
  }
  result.registered = true;

  // 3. Both images as luma on the comparison grid; marker squares masked out.
  const int dw = layout.display_width, dh = layout.display_height;
  const int gw = std::min(m.options.compare_width, dw);
  const int gh = std::max(1, static_cast<int>(std::lround(static_cast<double>(gw) * dh / dw)));
  const double bx = static_cast<double>(dw) / gw, by = static_cast<double>(dh) / gh;
  const std::size_t n = static_cast<std::size_t>(gw) * gh;
  m.ref.assign(n, 0.0f);
  m.cap.assign(n, 0.0f);
  m.valid.assign(n, 1);
  const int ms = layout.marker_size();
  for (int gy = 0; gy < gh; ++gy)
    for (int gx = 0; gx < gw; ++gx) {
      const int x0 = static_cast<int>(gx * bx), x1 = std::max(x0 + 1, static_cast<int>((gx + 1) * bx));
      const int y0 = static_cast<int>(gy * by), y1 = std::max(y0 + 1, static_cast<int>((gy + 1) * by));
      const std::size_t i = static_cast<std::size_t>(gy) * gw + gx;
      for (int k = 0; k < 4; ++k) {
        const auto [ox, oy] = layout.marker_origin(k);
        if (x0 < ox + ms && x1 > ox && y0 < oy + ms && y1 > oy) m.valid[i] = 0;
      }
      float sum = 0;
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) sum += luma(presented.at(x, y));
      m.ref[i] = sum / static_cast<float>((x1 - x0) * (y1 - y0));
      // 4x4 samples per cell through the homography approximate the same box filter in the capture.
      float csum = 0;
      for (int s = 0; s < 16; ++s) {
        const double px = x0 - 0.5 + (x1 - x0) * ((s % 4) + 0.5) / 4.0;
        const double py = y0 - 0.5 + (y1 - y0) * ((s / 4) + 0.5) / 4.0;
        const detail::Point c = detail::apply(h, px, py);
        csum += m.sample(cw, ch, c.x, c.y);
      }
      m.cap[i] = csum / 16.0f;
    }

  // 4. Exposure, gamma and white balance of the camera differ from the display: match the capture's
  // mean and contrast to the reference before comparing structure.
  double mr = 0, mc = 0, cnt = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (m.valid[i]) mr += m.ref[i], mc += m.cap[i], cnt += 1;
  if (cnt < 1) {
    result.reason = "display too small: markers cover the whole comparison area";
    return result;
  }
  mr /= cnt;
  mc /= cnt;
  double vr = 0, vc = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (m.valid[i]) vr += (m.ref[i] - mr) * (m.ref[i] - mr), vc += (m.cap[i] - mc) * (m.cap[i] - mc);
  const double sr = std::sqrt(vr / cnt), sc = std::sqrt(vc / cnt);
  // Below one grey level of spread the capture is flat (blank content): structure cannot match.
  const double gain = sc > 1.0 ? sr / sc : 0.0;
  for (std::size_t i = 0; i < n; ++i) m.cap[i] = static_cast<float>((m.cap[i] - mc) * gain + mr);

  m.warped.resize(gw, gh);
  for (std::size_t i = 0; i < n; ++i) {
    const auto v = static_cast<std::uint8_t>(std::clamp(std::lround(m.cap[i]), 0L, 255L));
    m.warped.pixels[i * 3] = m.warped.pixels[i * 3 + 1] = m.warped.pixels[i * 3 + 2] = v;
  }

  // 5. Mean SSIM over every fully unmasked window.
  const int win = m.options.ssim_window;
  const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
  double total = 0, weights = 0;
  int windows = 0;
  for (int wy = 0; wy + win <= gh; ++wy)
    for (int wx = 0; wx + win <= gw; ++wx) {
      double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
      bool ok = true;
      for (int y = wy; y < wy + win && ok; ++y)
        for (int x = wx; x < wx + win; ++x) {
          const std::size_t i = static_cast<std::size_t>(y) * gw + x;
          if (!m.valid[i]) {
            ok = false;
            break;
          }
          const double a = m.ref[i], b = m.cap[i];
          sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b;
        }
      if (!ok) continue;
      const double k = win * win;
      const double ua = sa / k, ub = sb / k;
      const double va = saa / k - ua * ua, vb = sbb / k - ub * ub, cov = sab / k - ua * ub;
      const double ssim = ((2 * ua * ub + c1) * (2 * cov + c2)) / ((ua * ua + ub * ub + c1) * (va + vb + c2));
      // Flat windows (sky, walls) score near 1 whatever is shown, so plain mean SSIM lets a wrong
      // scene with similar flat areas pass; weighting by local contrast counts the windows that can
      // tell pictures apart. A capture that is flat where the reference is not still weighs in.
      const double weight = std::sqrt(std::max(va, 0.0)) + std::sqrt(std::max(vb, 0.0)) + 1e-3;
      total += weight * ssim;
      weights += weight;
      ++windows;
    }
  if (windows == 0) {
    result.reason = "comparison grid has no unmasked window";
    return result;
  }
  result.score = total / weights;
  result.passed = result.score >= m.options.pass_threshold;
  result.reason = result.passed ? "ok"
                                : "picture differs from the presented frame (SSIM " + std::to_string(result.score) + " < " +
                                      std::to_string(m.options.pass_threshold) + ")";
  return result;
}

}  // namespace hal
