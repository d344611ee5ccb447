// gltf_corpus OUT_DIR: writes every case of the corpus (see corpus.h) into OUT_DIR.
#include "corpus.h"

#include <filesystem>
#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: gltf_corpus OUT_DIR\n";
    return 2;
  }
  std::error_code ec;
  std::filesystem::create_directories(argv[1], ec);
  if (ec) {
    std::cerr << "error: " << argv[1] << ": cannot create the folder: " << ec.message() << "\n";
    return 1;
  }
  const size_t written = corpus::write_all(argv[1]);
  std::cout << written << " files in " << argv[1] << "\n";
  return written == corpus::cases().size() ? 0 : 1;
}
