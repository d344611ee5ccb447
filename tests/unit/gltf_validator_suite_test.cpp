// The loader against Khronos' glTF-Validator on the validator's own test suite (372 files with the
// validator's expected reports, in ../shared/gltf-validator-test): a file the validator reports an
// error for is refused, a file without errors loads, except valid files with nothing to show and
// the disagreements listed with their reason in tests/gltf_corpus/validator_suite_disagreements.tsv.
#include "scene/gltf_loader.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace {
namespace fs = std::filesystem;

const fs::path kSuite = fs::path(PLAYER_SHARED_DIR) / "gltf-validator-test" / "test";

std::map<std::string, std::string> listed_disagreements() {
  std::map<std::string, std::string> listed;
  std::ifstream in(std::string(PLAYER_CORPUS_DIR) + "/validator_suite_disagreements.tsv");
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    const size_t tab = line.find('\t');
    listed[line.substr(0, tab)] = tab == std::string::npos ? "" : line.substr(tab + 1);
  }
  return listed;
}

bool nothing_to_show(const std::string& error) {
  return error.find(": scenes: the file has no scene with nodes to show") != std::string::npos ||
         error.find(": meshes: the scene contains no triangles to render") != std::string::npos;
}

TEST(GltfValidatorSuite, EveryFileAgreesWithItsExpectedReportOrIsAListedDisagreement) {
  ASSERT_TRUE(fs::is_directory(kSuite)) << kSuite << ": Khronos' validator suite must be beside the repository (../shared)";
  const auto listed = listed_disagreements();
  size_t files = 0, agree = 0, empty = 0;
  std::map<std::string, bool> seen;
  for (const auto& entry : fs::recursive_directory_iterator(kSuite)) {
    const fs::path& path = entry.path();
    if (path.extension() != ".gltf" && path.extension() != ".glb") continue;
    const fs::path report_path = path.string() + ".report.json";
    if (!fs::exists(report_path)) continue;  // a resource another file names
    ++files;
    const std::string name = fs::relative(path, kSuite).generic_string();
    std::ifstream report_file(report_path);
    const int errors = nlohmann::json::parse(report_file)["issues"]["numErrors"].get<int>();
    scene::Scene scene;
    scene::LoadReport report;
    const bool loads = scene::load_gltf(path, scene, report);
    if (!loads) {
      EXPECT_NE(report.error.find(path.string()), std::string::npos) << name << ": " << report.error;
    }
    const bool agrees = (errors > 0) != loads;
    const bool empty_scene = errors == 0 && !loads && nothing_to_show(report.error);
    if (listed.count(name)) {
      seen[name] = true;
      EXPECT_FALSE(agrees || empty_scene) << name << " is listed as a disagreement but agrees: remove it from the list";
    } else if (empty_scene) {
      ++empty;
    } else {
      EXPECT_TRUE(agrees) << name << ": the validator reports " << errors << " errors, the loader "
                          << (loads ? "loads it" : "refuses it: " + report.error) << "; fix one, or list it with the reason";
      agree += agrees;
    }
  }
  for (const auto& [name, reason] : listed) {
    EXPECT_TRUE(seen.count(name)) << name << ": listed, but the suite has no such file";
    EXPECT_FALSE(reason.empty()) << name << ": listed without a reason";
  }
  EXPECT_EQ(files, 372u) << "the suite's asset count changed";
  std::cout << files << " files: " << agree << " agree, " << empty << " valid with nothing to show, " << listed.size()
            << " listed disagreements\n";
}

}  // namespace
