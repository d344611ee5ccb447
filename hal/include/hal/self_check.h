#pragma once
// Display self-check: does the check camera see the frame the player presented?
//
// Registration: during a check the player presents its frame with four AprilTag (tag36h11) markers
// flush in the screen corners (draw_fiducials). Their 16 detected corners give a homography from
// display to camera; the capture is warped into display space and compared with the presented frame
// by contrast-weighted SSIM on downsampled, contrast-normalised luma, the tag squares masked out. Markers flush with
// the corners make a shifted or cropped picture lose a marker, and the marker ids change with every
// check so a frozen screen still showing an old check frame is recognised as such.
#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "hal/image.h"

namespace hal {

struct FiducialLayout {
  int display_width = 0;
  int display_height = 0;
  int cell = 0;      // display pixels per tag cell; a marker with its white border is 10 cells
  int first_id = 0;  // corner i (top-left, top-right, bottom-right, bottom-left) shows first_id + i

  // Markers about 1/7 of the shorter side; ids advance with `sequence` (the check number).
  static FiducialLayout for_display(int width, int height, std::uint32_t sequence);
  int marker_size() const { return cell * 10; }
  // Top-left pixel of the marker (white border included) in corner i.
  std::array<int, 2> marker_origin(int corner) const;
};

// Paints the four markers over `frame` (which must be display_width x display_height).
void draw_fiducials(RgbImage& frame, const FiducialLayout& layout);

struct SelfCheckOptions {
  int compare_width = 160;  // luma grid width the comparison runs at; height keeps the aspect
  int ssim_window = 7;      // SSIM window, grid cells
  // Midway between the worst correct frame (0.96, 1.5 px lens blur) and the best wrong one that
  // still registered (0.66, a different scene of the same layout) in tests/hal/self_check_test.cpp.
  double pass_threshold = 0.8;
};

struct SelfCheckResult {
  bool passed = false;
  double score = 0.0;  // contrast-weighted mean SSIM in [-1, 1]; 0 when registration failed
  int markers_found = 0;
  bool registered = false;
  std::string reason;  // why it failed, or "ok"
};

class DisplayChecker {
 public:
  explicit DisplayChecker(SelfCheckOptions options = {});
  ~DisplayChecker();
  DisplayChecker(const DisplayChecker&) = delete;
  DisplayChecker& operator=(const DisplayChecker&) = delete;

  // `presented` is the frame with markers as shown (layout.display_width x display_height);
  // `capture` is the camera frame of any size.
  SelfCheckResult check(const RgbImage& presented, const FiducialLayout& layout, const RgbImage& capture);

  // The last capture warped into display space at the comparison resolution (grey as RGB), for
  // diagnostics when a check fails.
  const RgbImage& last_warped() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace hal
