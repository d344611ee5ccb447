// The fuzz targets outside the fuzz preset: each is linked with this main instead of libFuzzer's,
// so every build (debug, asan, release with GCC) runs the committed seeds and regression files
// through LLVMFuzzerTestOneInput once. A crash is the test failing; the last "input:" line names
// the file. Folders are read flat (their subfolders, e.g. regressions/<target>/open/, are not).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  for (int i = 1; i < argc; ++i) {
    const fs::path arg = argv[i];
    std::error_code ec;
    if (fs::is_regular_file(arg, ec)) {
      files.push_back(arg);
    } else if (fs::is_directory(arg, ec)) {
      for (const fs::directory_entry& entry : fs::directory_iterator(arg))
        if (entry.is_regular_file()) files.push_back(entry.path());
    } else {
      std::fprintf(stderr, "%s: expected a file or a folder of inputs\n", arg.c_str());
      return 2;
    }
  }
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    std::fprintf(stderr, "input: %s\n", file.c_str());
    // Exactly the input's size on the heap, so ASan sees a read one past its end.
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(file, ec);
    std::ifstream in(file, std::ios::binary);
    std::vector<std::uint8_t> copy(ec ? 0 : size);
    if (ec || !in || !in.read(reinterpret_cast<char*>(copy.data()), static_cast<std::streamsize>(copy.size()))) {
      std::fprintf(stderr, "%s: cannot read\n", file.c_str());
      return 2;
    }
    static std::uint8_t none = 0;  // libFuzzer never passes a null pointer, even for an empty input
    LLVMFuzzerTestOneInput(copy.empty() ? &none : copy.data(), copy.size());
  }
  std::printf("%zu inputs ran without a crash\n", files.size());
  return 0;
}
