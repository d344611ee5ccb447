// Program binaries kept on disk: a second start loads what the first compiled and draws alike; a
// changed source, a damaged file or one the driver refuses is compiled anew, never loaded.
#include "harness.h"

#include "gl/program_store.h"

#include "base/cache_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

namespace {

namespace fs = std::filesystem;

// A program that fills the surface with one colour: which colour shows which source was linked.
std::vector<gl::StageSource> fill_program(const char* colour) {
  const std::string vertex =
      "#version 310 es\n"
      "void main() {\n"
      "  vec2 corner = vec2(float((gl_VertexID & 1) << 2), float((gl_VertexID & 2) << 1)) - 1.0;\n"
      "  gl_Position = vec4(corner, 0.0, 1.0);\n"
      "}\n";
  const std::string fragment =
      std::string("#version 310 es\nprecision mediump float;\nout vec4 colour;\nvoid main() { colour = ") + colour + "; }\n";
  return {{GL_VERTEX_SHADER, "fill.vert", "default", vertex}, {GL_FRAGMENT_SHADER, "fill.frag", "default", fragment}};
}

const char* const kRed = "vec4(1.0, 0.0, 0.0, 1.0)";
const char* const kGreen = "vec4(0.0, 1.0, 0.0, 1.0)";

class ProgramStore : public test::SessionTest {
 protected:
  void SetUp() override {
    test::SessionTest::SetUp();
    if (HasFatalFailure()) return;
    std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    for (char& c : name) c = c == '/' ? '_' : c;  // a parameterised test's name ends in /N
    dir_ = (fs::temp_directory_path() / ("player-program-store-" + std::to_string(getpid()) + "-" + name)).string();
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A start of the player: a fresh program cache (nothing in memory) over the store's folder.
  std::unique_ptr<gl::ProgramCache> start() {
    auto cache = std::make_unique<gl::ProgramCache>();
    std::string reason;
    std::unique_ptr<gl::ProgramStore> store = gl::ProgramStore::open(dir_, session_->caps(), reason);
    EXPECT_TRUE(store) << reason;  // Mesa offers a binary format while its own shader cache is on
    if (store) cache->use_store(std::move(store));
    return cache;
  }

  // The colour the program draws over the surface, as bytes.
  std::array<uint8_t, 4> draw(const gl::Program& program) {
    GLuint id = 0;
    gl::api.GenVertexArrays(1, &id);
    const gl::VertexArray vertices(id);
    gl::api.BindFramebuffer(GL_FRAMEBUFFER, session_->platform().framebuffer());
    gl::api.Viewport(0, 0, 64, 48);
    gl::api.Disable(GL_DEPTH_TEST);
    gl::api.BindVertexArray(vertices.id());
    gl::api.UseProgram(program.id());
    gl::api.DrawArrays(GL_TRIANGLES, 0, 3);
    std::array<uint8_t, 4> pixel{};
    gl::api.BindFramebuffer(GL_READ_FRAMEBUFFER, session_->platform().framebuffer());
    gl::api.ReadPixels(32, 24, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, pixel.data());
    gl::api.BindVertexArray(0);
    EXPECT_EQ(gl::api.GetError(), static_cast<GLenum>(GL_NO_ERROR));
    return pixel;
  }

  const gl::Program* get(gl::ProgramCache& cache, const char* colour) {
    std::string error;
    const gl::Program* program = cache.get(fill_program(colour), error);
    EXPECT_NE(program, nullptr) << error;
    return program;
  }

  std::string file_of(gl::ProgramCache& cache, const char* colour) { return cache.store()->path_for(fill_program(colour)); }

  // A start that finds the program's file wrong: refuses it, compiles, and draws the right colour.
  std::unique_ptr<gl::ProgramCache> expect_refused_and_compiled(const char* colour, const std::array<uint8_t, 4>& bytes) {
    auto cache = start();
    const gl::Program* program = get(*cache, colour);
    EXPECT_TRUE(program);
    EXPECT_EQ(cache->store()->rejected(), 1u);
    EXPECT_EQ(cache->store()->loaded(), 0u);
    EXPECT_EQ(cache->compiled(), 1u);
    if (program) {
      EXPECT_EQ(draw(*program), bytes);
    }
    return cache;
  }

  std::string dir_;
};

const std::array<uint8_t, 4> kRedBytes{255, 0, 0, 255};
const std::array<uint8_t, 4> kGreenBytes{0, 255, 0, 255};

TEST_P(ProgramStore, ASecondStartLoadsWhatTheFirstCompiledAndDrawsAlike) {
  const auto first = start();
  ASSERT_TRUE(first->store());
  const gl::Program* compiled = get(*first, kRed);
  ASSERT_TRUE(compiled);
  EXPECT_EQ(first->compiled(), 1u);
  EXPECT_EQ(first->store()->loaded(), 0u);
  EXPECT_EQ(first->store_problem(), "");
  EXPECT_TRUE(fs::is_regular_file(file_of(*first, kRed)));
  EXPECT_EQ(draw(*compiled), kRedBytes);

  const auto second = start();
  const gl::Program* loaded = get(*second, kRed);
  ASSERT_TRUE(loaded);
  EXPECT_EQ(second->compiled(), 0u);
  EXPECT_EQ(second->store()->loaded(), 1u);
  EXPECT_EQ(second->store()->rejected(), 0u);
  EXPECT_EQ(draw(*loaded), kRedBytes);
  // Asked again in the same start, it comes from memory: neither compiled nor loaded again.
  EXPECT_EQ(get(*second, kRed), loaded);
  EXPECT_EQ(second->store()->loaded(), 1u);
}

TEST_P(ProgramStore, AChangedSourceIsCompiledNeverLoaded) {
  get(*start(), kRed);
  const auto next = start();
  const gl::Program* changed = get(*next, kGreen);  // the same files, one line of the fragment stage changed
  ASSERT_TRUE(changed);
  EXPECT_EQ(next->compiled(), 1u);
  EXPECT_EQ(next->store()->loaded(), 0u);
  EXPECT_EQ(draw(*changed), kGreenBytes);
  EXPECT_NE(file_of(*next, kGreen), file_of(*next, kRed));
  // Both are kept: switching back needs no compile.
  const auto after = start();
  EXPECT_EQ(draw(*get(*after, kRed)), kRedBytes);
  EXPECT_EQ(draw(*get(*after, kGreen)), kGreenBytes);
  EXPECT_EQ(after->compiled(), 0u);
  EXPECT_EQ(after->store()->loaded(), 2u);
}

// Each way a file can be wrong: its binary damaged (one byte), cut short, its key check changed, a
// binary format the driver does not know in a file sealed again around it (so only the driver
// refuses it), or not a program file at all. Each is compiled anew and replaced, so the start after
// loads again.
TEST_P(ProgramStore, ADamagedOrRefusedFileIsCompiledAnewAndReplaced) {
  using Damage = void (*)(std::string&);
  const std::vector<std::pair<const char*, Damage>> damages = {
      {"one byte of the binary", [](std::string& bytes) { bytes[bytes.size() / 2 + 16] ^= 0x20; }},
      {"cut short", [](std::string& bytes) { bytes.resize(bytes.size() / 2); }},
      {"the key check", [](std::string& bytes) { bytes[8] ^= 0x01; }},
      {"a format the driver refuses",
       [](std::string& bytes) {
         // The seal's header: magic (8 bytes), key check (8), length (8), checksum (8); the payload
         // starts with the format.
         std::string payload = bytes.substr(32);
         payload[0] ^= 0x40;
         std::uint64_t key_check = 0;
         std::memcpy(&key_check, bytes.data() + 8, sizeof key_check);
         bytes = base::seal_cache_payload(bytes.substr(0, 8), key_check, payload);
       }},
      {"not a program file", [](std::string& bytes) { bytes = "not a program binary\n"; }},
  };
  for (const auto& [what, damage] : damages) {
    SCOPED_TRACE(what);
    fs::remove_all(dir_);
    const auto first = start();
    get(*first, kRed);
    const std::string path = file_of(*first, kRed);
    std::string bytes;
    {
      std::ifstream in(path, std::ios::binary);
      bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    ASSERT_GT(bytes.size(), 64u);
    damage(bytes);
    std::ofstream(path, std::ios::binary | std::ios::trunc).write(bytes.data(), static_cast<std::streamsize>(bytes.size()));

    expect_refused_and_compiled(kRed, kRedBytes);

    const auto after = start();
    EXPECT_EQ(draw(*get(*after, kRed)), kRedBytes);
    EXPECT_EQ(after->store()->loaded(), 1u);
    EXPECT_EQ(after->compiled(), 0u);
  }
}

// A save cut short (the disk full mid-write, here /dev/full in the partial file's place) fails with
// the file named, leaves nothing behind, neither the partial file nor one under the name load reads,
// and the next start compiles.
TEST_P(ProgramStore, ASaveThatFailsMidWriteLeavesNothing) {
  std::string reason, error;
  const std::unique_ptr<gl::ProgramStore> store = gl::ProgramStore::open(dir_, session_->caps(), reason);
  ASSERT_TRUE(store) << reason;
  const std::vector<gl::StageSource> sources = fill_program(kRed);
  const gl::Program program = gl::link_program(sources, error, true);
  ASSERT_TRUE(program) << error;
  const std::string path = store->path_for(sources);
  const std::string partial = path + ".partial." + std::to_string(getpid());
  fs::create_symlink("/dev/full", partial);
  EXPECT_FALSE(store->save(sources, program, error));
  EXPECT_EQ(error, "cannot write " + partial);
  EXPECT_FALSE(fs::exists(fs::symlink_status(partial)));
  EXPECT_FALSE(fs::exists(path));
  const auto next = start();
  get(*next, kRed);
  EXPECT_EQ(next->compiled(), 1u);
  EXPECT_EQ(next->store()->loaded(), 0u);
  // A save that works leaves the one file, nothing partial.
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(dir_)) {
    ++files;
    EXPECT_EQ(entry.path().extension(), ".bin") << entry.path();
  }
  EXPECT_EQ(files, 1u);
}

// A whole, valid file under another program's name (as a collision of the file names' hash would
// leave it) is refused by the second key in its header: compiled anew, never drawn with.
TEST_P(ProgramStore, AValidFileUnderAnotherProgramsNameIsNeverLoaded) {
  const auto first = start();
  get(*first, kRed);
  const std::string red = file_of(*first, kRed), green = file_of(*first, kGreen);
  fs::copy_file(red, green);
  const auto next = expect_refused_and_compiled(kGreen, kGreenBytes);
  // Sources that differ only in their last bytes, or only in a stage's type, are other programs too.
  std::vector<gl::StageSource> tail = fill_program(kGreen), type = fill_program(kGreen);
  tail[1].text += "//x";
  std::swap(type[0].type, type[1].type);
  EXPECT_NE(next->store()->path_for(tail), green);
  EXPECT_NE(next->store()->path_for(type), green);
}

// The folder stays bounded: opening it removes the least recently used files beyond the limit, and
// a program loaded counts as used.
TEST_P(ProgramStore, OpeningRemovesTheLeastRecentlyUsedFilesBeyondTheLimit) {
  const auto first = start();
  get(*first, kRed);
  const std::string kept = file_of(*first, kRed);
  const auto now = fs::file_time_type::clock::now();
  fs::last_write_time(kept, now - std::chrono::hours(1000));
  get(*start(), kRed);  // loaded: used now, so it is the newest
  const size_t extra = gl::ProgramStore::kMaxFiles + 8;
  for (size_t i = 0; i < extra; ++i) {
    const fs::path path = fs::path(dir_) / ("old-" + std::to_string(i) + ".bin");
    std::ofstream(path) << "x";
    fs::last_write_time(path, now - std::chrono::hours(extra - i));
  }
  start();
  size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir_)) ++files;
  EXPECT_EQ(files, gl::ProgramStore::kMaxFiles);
  EXPECT_TRUE(fs::exists(kept));
  for (size_t i = 0; i < 9; ++i) EXPECT_FALSE(fs::exists(fs::path(dir_) / ("old-" + std::to_string(i) + ".bin"))) << i;
  EXPECT_TRUE(fs::exists(fs::path(dir_) / "old-9.bin"));
}

INSTANTIATE_TEST_SUITE_P(Platforms, ProgramStore, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace
