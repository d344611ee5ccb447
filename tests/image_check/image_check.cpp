// Opens images a CLI test asked a command to write and checks what is in them, for
// tests/hal/expect_output.cmake (-DCHECK=...): the size and channels, and that they hold a picture
// rather than one value everywhere (a clear colour, a zeroed buffer, a read of the wrong target).
//
//   image_check --size WxH [--channels N] [--min-colours N] [--max-share F] FILE... [--option ... FILE...]
//
// Each file is checked against the options given before it, so one run checks files of different
// kinds. --min-colours: at least N distinct pixel values (default 2: not uniform). --max-share: no
// one pixel value covers more than the fraction F of the image (the background alone must not fill
// it). Each failure is one line "FILE: <what>: expected <value>, got <value>". Exit 0 when every
// file passes, 1 when one fails, 2 on bad arguments.
#include <OpenImageIO/imagebuf.h>

#include <algorithm>
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
};

int usage(const std::string& why) {
  std::fprintf(stderr, "image_check: %s\nusage: image_check --size WxH [--channels N] [--min-colours N] [--max-share F] FILE...\n",
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
    failures.push_back(path + ": channels: expected " + std::to_string(want.channels) + ", got " + std::to_string(spec.nchannels));
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
