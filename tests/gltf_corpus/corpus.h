#pragma once
// A deterministic corpus of glTF files, valid and malformed, one file per class: the seeds for
// fuzzing, the files a validator comparison runs on, and the inputs of the loader's unit tests.
// Every file is self-contained (buffers and images are data URIs or GLB chunks), so a case is
// its bytes alone.
#include <string>
#include <vector>

namespace corpus {

struct Case {
  std::string name;  // the file name, e.g. "stride-below-element.gltf"
  bool valid;        // Khronos' glTF-Validator reports no error for it (tests/gltf_corpus/validator_verdicts.tsv)
  std::string (*make)();
};

// Every case, in a fixed order; names are unique.
const std::vector<Case>& cases();

// The bytes of case `name`; throws std::out_of_range for an unknown name.
std::string bytes_of(const std::string& name);

// Writes every case into `dir` (which must exist); returns the number of files written.
size_t write_all(const std::string& dir);

}  // namespace corpus
