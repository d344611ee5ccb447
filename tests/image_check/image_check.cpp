// Opens images a CLI test asked a command to write and checks what is in them, for
// tests/hal/expect_output.cmake (-DCHECK=...): the size and channels, and that they hold a picture
// rather than one value everywhere (a clear colour, a zeroed buffer, a read of the wrong target).
//
//   image_check --size WxH [--channels N] [--min-colours N] [--max-share F] [--same-as REF [--max-diff N]
//               [--turned DEG]] FILE...
//               [--option ... FILE...]
//
// Each file is checked against the options given before it, so one run checks files of different
// kinds. --min-colours: at least N distinct pixel values (default 2: not uniform). --max-share: no
// one pixel value covers more than the fraction F of the image (the background alone must not fill
// it). --same-as: the colour channels (RGB) of each pixel differ from REF's by at most N (8-bit steps,
// --max-diff, default 0), and the count and worst difference are printed; with --turned DEG (90, 180,
// 270) each file is compared with REF turned that far clockwise, as the player's --rotation turns it. Each failure is one line
// "FILE: <what>: expected <value>, got <value>". Exit 0 when every file passes, 1 when one fails, 2 on bad arguments.
#include <OpenImageIO/imagebuf.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

namespace {

struct Checks {
  int width = 0, height = 0, channels = 0;  // channels 0: any
  std::size_t min_colours = 2;              // 2: not uniform
  double max_share = 1.0;
  std::string same_as;    // empty: no comparison
  double max_diff = 0.0;  // in 8-bit steps
  int turned = 0;         // degrees clockwise
};

int usage(const std::string& why) {
  std::fprintf(stderr,
               "image_check: %s\nusage: image_check --size WxH [--channels N] [--min-colours N] [--max-share F] FILE...\n",
               why.c_str());
  return 2;
}

// Returns the failures for one file, one line each.
std::vector<std::string> check(const std::string& path, const Checks& want) {
  OIIO::ImageBuf image(path);
  if (!image.read(0, 0, true, OIIO::TypeDesc::FLOAT)) return {path + ": cannot read as an image (" + image.geterror() + ")"};
  const OIIO::ImageSpec& spec = image.spec();
  std::vector<std::string> failures;
  if (spec.width != want.width || spec.height != want.height)
    failures.push_back(path + ": size: expected " + std::to_string(want.width) + "x" + std::to_string(want.height) + ", got " +
                       std::to_string(spec.width) + "x" + std::to_string(spec.height));
  if (want.channels != 0 && spec.nchannels != want.channels)
    failures.push_back(path + ": channels: expected " + std::to_string(want.channels) + ", got " +
                       std::to_string(spec.nchannels));
  // Distinct pixel values, counted exactly (8-bit files hold few; float files are compared as stored).
  std::map<std::vector<float>, std::size_t> counts;
  std::vector<float> pixel(static_cast<std::size_t>(spec.nchannels));
  for (int y = 0; y < spec.height; ++y)
    for (int x = 0; x < spec.width; ++x) {
      image.getpixel(x, y, pixel.data(), spec.nchannels);
      ++counts[pixel];
    }
  std::size_t most = 0;
  for (const auto& [value, n] : counts) most = std::max(most, n);
  const double pixels = static_cast<double>(spec.width) * spec.height;
  if (counts.size() < want.min_colours)
    failures.push_back(path + ": distinct pixel values: expected at least " + std::to_string(want.min_colours) + ", got " +
                       std::to_string(counts.size()) + (counts.size() == 1 ? " (the image is uniform)" : ""));
  if (pixels > 0 && static_cast<double>(most) / pixels > want.max_share) {
    char text[160];
    std::snprintf(text, sizeof text, ": most common pixel value: expected at most %.0f%% of the pixels, got %.1f%%",
                  want.max_share * 100.0, 100.0 * static_cast<double>(most) / pixels);
    failures.push_back(path + text);
  }
  if (!want.same_as.empty()) {
    OIIO::ImageBuf reference(want.same_as);
    if (!reference.read(0, 0, true, OIIO::TypeDesc::FLOAT)) {
      failures.push_back(path + ": --same-as " + want.same_as + ": cannot read as an image (" + reference.geterror() + ")");
      return failures;
    }
    const OIIO::ImageSpec& ref = reference.spec();
    const bool quarter = want.turned == 90 || want.turned == 270;
    const int ref_width = quarter ? ref.height : ref.width, ref_height = quarter ? ref.width : ref.height;
    if (ref_width != spec.width || ref_height != spec.height || ref.nchannels < 3 || spec.nchannels < 3) {
      failures.push_back(path + ": --same-as " + want.same_as + ": expected the same size with RGB, got " +
                         std::to_string(ref.width) + "x" + std::to_string(ref.height) + "x" + std::to_string(ref.nchannels) +
                         " against " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + "x" +
                         std::to_string(spec.nchannels));
      return failures;
    }
    std::vector<float> other(static_cast<std::size_t>(ref.nchannels));
    double worst = 0.0;
    std::size_t differing = 0;
    for (int y = 0; y < spec.height; ++y)
      for (int x = 0; x < spec.width; ++x) {
        image.getpixel(x, y, pixel.data(), spec.nchannels);
        // The reference pixel this one shows when the reference is turned clockwise (rows from the top).
        int rx = x, ry = y;
        if (want.turned == 90)
          rx = y, ry = ref.height - 1 - x;
        else if (want.turned == 180)
          rx = ref.width - 1 - x, ry = ref.height - 1 - y;
        else if (want.turned == 270)
          rx = ref.width - 1 - y, ry = x;
        reference.getpixel(rx, ry, other.data(), ref.nchannels);
        double here = 0.0;
        for (int c = 0; c < 3; ++c) here = std::max(here, std::abs(static_cast<double>(pixel[c]) - other[c]) * 255.0);
        worst = std::max(worst, here);
        differing += here > 0.5 ? 1 : 0;
      }
    std::printf("%s: against %s: %zu of %.0f pixels differ, by at most %.0f/255\n", path.c_str(), want.same_as.c_str(), differing,
                pixels, worst);
    if (worst > want.max_diff + 0.5) {
      char text[160];
      std::snprintf(text, sizeof text, ": difference from the reference: expected at most %.0f/255, got %.0f/255", want.max_diff,
                    worst);
      failures.push_back(path + text);
    }
  }
  return failures;
}

}  // namespace

int main(int argc, char** argv) {
  Checks want;
  int failed = 0, checked = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool has_value = i + 1 < argc;
    if (arg == "--size" && has_value) {
      char x = 0;
      if (std::sscanf(argv[++i], "%d%c%d", &want.width, &x, &want.height) != 3 || x != 'x' || want.width < 1 || want.height < 1)
        return usage(std::string("--size: expected WxH with positive integers, got '") + argv[i] + "'");
    } else if (arg == "--channels" && has_value) {
      want.channels = std::atoi(argv[++i]);
    } else if (arg == "--min-colours" && has_value) {
      want.min_colours = static_cast<std::size_t>(std::atoi(argv[++i]));
    } else if (arg == "--max-share" && has_value) {
      want.max_share = std::atof(argv[++i]);
    } else if (arg == "--same-as" && has_value) {
      want.same_as = argv[++i];
    } else if (arg == "--max-diff" && has_value) {
      want.max_diff = std::atof(argv[++i]);
    } else if (arg == "--turned" && has_value) {
      want.turned = std::atoi(argv[++i]);
      if (want.turned != 0 && want.turned != 90 && want.turned != 180 && want.turned != 270)
        return usage(std::string("--turned: expected 0, 90, 180 or 270, got '") + argv[i] + "'");
    } else if (arg.rfind("--", 0) == 0) {
      return usage("unknown option or missing value: " + arg);
    } else {
      if (want.width == 0) return usage("--size is required before " + arg);
      const std::vector<std::string> failures = check(arg, want);
      for (const std::string& f : failures) std::printf("%s\n", f.c_str());
      if (failures.empty()) std::printf("%s: ok\n", arg.c_str());
      failed += failures.empty() ? 0 : 1;
      ++checked;
    }
  }
  if (checked == 0) return usage("no files to check");
  return failed == 0 ? 0 : 1;
}
