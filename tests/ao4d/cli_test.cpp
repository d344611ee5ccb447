// The ao4d command end to end: exit codes and messages for bad input, and --points output.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <sys/wait.h>

namespace {

struct Result {
    int status = -1;
    std::string output;  // stdout and stderr together
};

Result run(const std::string& args) {
    Result r;
    FILE* pipe = popen((std::string(AO4D_CLI) + " " + args + " 2>&1").c_str(), "r");
    if (!pipe) return r;
    std::array<char, 4096> buffer;
    while (const std::size_t n = std::fread(buffer.data(), 1, buffer.size(), pipe)) r.output.append(buffer.data(), n);
    const int status = pclose(pipe);
    r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return r;
}

std::filesystem::path write(const std::string& name, const std::string& text) {
    const auto file = std::filesystem::path(AO4D_TEST_OUTPUT_DIR) / name;
    std::ofstream(file) << text;
    return file;
}

// A unit cell in w = 0 facing +w, as a mesh file.
const char* kFloor = "v -1 -1 0 0\nv 3 -1 0 0\nv -1 3 0 0\nv -1 -1 3 0\nt 1 2 3 4\n";

TEST(Cli, BadMeshFailsNamingTheFileAndLine) {
    const auto mesh = write("bad.tet4", "v 0 0 0 0\nv 1 0 0 0\nt 1 2 x 4\n");
    const Result r = run("--mesh " + mesh.string() + " -o " + (mesh.parent_path() / "bad").string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find(mesh.string() + ":3: expected a 1-based vertex index, got 'x'"), std::string::npos) << r.output;
}

TEST(Cli, BadPointsFailNamingTheFileAndLine) {
    const auto mesh = write("floor.tet4", kFloor);
    const auto points = write("bad.points", "0 0 0 0 0 0 0 1\n0 0 0\n");
    const Result r = run("--mesh " + mesh.string() + " --points " + points.string());
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find(points.string() + ":2: expected 8 numbers"), std::string::npos) << r.output;
}

TEST(Cli, MissingSourceOrOutputIsAUsageError) {
    EXPECT_NE(run("--rays 4").status, 0);
    EXPECT_NE(run("--shape hypersphere").status, 0);
    const Result r = run("--shape nosuch -o x");
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.output.find("unknown shape 'nosuch'"), std::string::npos) << r.output;
}

TEST(Cli, PointsModePrintsOneValuePerLine) {
    const auto mesh = write("floor.tet4", kFloor);
    // On the plane facing away from it, then 0.5 above it facing it with rays of length 1.
    const auto points = write("ok.points", "0 0 0 0 0 0 0 1\n0 0 0 0.5 0 0 0 -1\n");
    const Result r = run("--mesh " + mesh.string() + " --points " + points.string() + " --rays 4000 --radius 1 --seed 3 -q");
    ASSERT_EQ(r.status, 0) << r.output;
    double a = -1, b = -1;
    ASSERT_EQ(std::sscanf(r.output.c_str(), "%lf\n%lf\n", &a, &b), 2) << r.output;
    EXPECT_EQ(a, 0.0);
    EXPECT_GT(b, 0.0);
    EXPECT_LT(b, 0.391);  // the cell is finite, so below the infinite plane's value
}

TEST(Cli, HelpDescribesTheOptions) {
    const Result r = run("--help");
    EXPECT_EQ(r.status, 0);
    for (const char* option : {"--shape", "--mesh", "--points", "--size", "--rays", "--radius", "--seed", "--cosine"})
        EXPECT_NE(r.output.find(option), std::string::npos) << option;
}

}  // namespace
