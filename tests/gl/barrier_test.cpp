// The memory barriers between passes, checked against the rules of the GL ES 3.1 specification
// (section 7.11.2) on a record of the GL calls of real frames. On llvmpipe a missing barrier changes
// no pixel (its compute dispatches finish before they return), so no picture comparison can notice
// one; a GPU that overlaps dispatches would show it as flicker. The record sees it everywhere.
//
// Tracked: the program in use, the textures on each sampler unit and image unit, and every
// glMemoryBarrier. At each dispatch and draw the program's active sampler and image uniforms say
// which units it reads and writes (asked from GL). Image stores are incoherent; the rules checked:
//   - a texture fetch sees an earlier command's image stores only after a barrier with
//     GL_TEXTURE_FETCH_BARRIER_BIT (read after write);
//   - an image load sees them only after GL_SHADER_IMAGE_ACCESS_BARRIER_BIT (read after write);
//   - an image store waits for an earlier command's fetches of the same texture only after
//     GL_SHADER_IMAGE_ACCESS_BARRIER_BIT (write after read: the next frame's AO must not overwrite
//     what the present pass is still reading).
// Stores are tracked per mip level, fetches per texture: a fetch reads every level but those its
// own command stores into (the depth chain samples level L - 1 of the texture whose level L it
// writes). For the write-after-read rule a command that samples and stores one texture does not
// count as sampling it, since which levels it reads is not known from the calls.
#include "harness.h"

#include <map>
#include <set>
#include <string>
#include <vector>

namespace {

constexpr int kSide = 64;

struct ImageBinding {
  GLuint texture = 0;
  GLint level = 0;
  GLenum access = GL_READ_ONLY;
};

using Level = std::pair<GLuint, GLint>;  // texture, mip level

struct Record {
  std::map<GLuint, GLuint> samplers;      // unit -> texture
  std::map<GLuint, ImageBinding> images;  // image unit -> binding
  std::set<Level> stored_unfetchable;     // image stores not yet visible to texture fetches
  std::set<Level> stored_unloadable;      // ... nor to image loads
  std::set<GLuint> fetched_unfenced;      // fetched by a command no image-access barrier followed yet
  int commands = 0;
  int coarser_level_stores = 0;  // stores into a level > 0: the depth chain ran
  int barriers = 0;
  std::vector<std::string> hazards;

  // A dispatch or draw whose program samples `sampler_units` and uses `image_units`.
  void command(const char* what, const std::set<GLuint>& sampler_units, const std::set<GLuint>& image_units) {
    ++commands;
    const std::string where = std::string(what) + " #" + std::to_string(commands);
    std::set<GLuint> fetched, stored_textures;
    std::set<Level> loaded, stored;
    for (GLuint unit : sampler_units)
      if (samplers[unit] != 0) fetched.insert(samplers[unit]);
    for (GLuint unit : image_units) {
      const ImageBinding& image = images[unit];
      if (image.texture == 0) continue;
      if (image.access != GL_WRITE_ONLY) loaded.insert({image.texture, image.level});
      if (image.access != GL_READ_ONLY) {
        stored.insert({image.texture, image.level});
        stored_textures.insert(image.texture);
      }
    }
    for (const Level& pending : stored_unfetchable)
      if (fetched.count(pending.first) && !stored.count(pending))
        hazards.push_back(where + " samples texture " + std::to_string(pending.first) + " (level " +
                          std::to_string(pending.second) + " stored before) with no GL_TEXTURE_FETCH_BARRIER_BIT between");
    for (const Level& level : loaded)
      if (stored_unloadable.count(level))
        hazards.push_back(where + " loads image " + std::to_string(level.first) +
                          " after image stores with no GL_SHADER_IMAGE_ACCESS_BARRIER_BIT between");
    for (GLuint texture : stored_textures)
      if (fetched_unfenced.count(texture))
        hazards.push_back(where + " stores into texture " + std::to_string(texture) +
                          " that an earlier command samples, with no GL_SHADER_IMAGE_ACCESS_BARRIER_BIT between");
    for (GLuint texture : fetched)
      if (!stored_textures.count(texture)) fetched_unfenced.insert(texture);
    for (const Level& level : stored) {
      stored_unfetchable.insert(level);
      stored_unloadable.insert(level);
      if (level.second > 0) ++coarser_level_stores;
    }
  }

  void barrier(GLbitfield bits) {
    ++barriers;
    if (bits & GL_TEXTURE_FETCH_BARRIER_BIT) stored_unfetchable.clear();
    if (bits & GL_SHADER_IMAGE_ACCESS_BARRIER_BIT) {
      stored_unloadable.clear();
      fetched_unfenced.clear();
    }
  }
};

Record* record = nullptr;
gl::Api real;
PFNGLGETACTIVEUNIFORMPROC get_active_uniform = nullptr;
PFNGLGETUNIFORMIVPROC get_uniform_iv = nullptr;
GLuint program_in_use = 0;
GLenum active_unit = 0;

bool is_sampler(GLenum type) {
  switch (type) {
    case GL_SAMPLER_2D:
    case GL_SAMPLER_3D:
    case GL_SAMPLER_CUBE:
    case GL_SAMPLER_2D_SHADOW:
    case GL_SAMPLER_2D_ARRAY:
    case GL_SAMPLER_2D_ARRAY_SHADOW:
    case GL_SAMPLER_CUBE_SHADOW:
    case GL_INT_SAMPLER_2D:
    case GL_INT_SAMPLER_3D:
    case GL_INT_SAMPLER_2D_ARRAY:
    case GL_UNSIGNED_INT_SAMPLER_2D:
    case GL_UNSIGNED_INT_SAMPLER_3D:
    case GL_UNSIGNED_INT_SAMPLER_2D_ARRAY:
      return true;
    default:
      return false;
  }
}

bool is_image(GLenum type) {
  switch (type) {
    case GL_IMAGE_2D:
    case GL_IMAGE_3D:
    case GL_IMAGE_CUBE:
    case GL_IMAGE_2D_ARRAY:
    case GL_INT_IMAGE_2D:
    case GL_INT_IMAGE_3D:
    case GL_INT_IMAGE_2D_ARRAY:
    case GL_UNSIGNED_INT_IMAGE_2D:
    case GL_UNSIGNED_INT_IMAGE_3D:
    case GL_UNSIGNED_INT_IMAGE_2D_ARRAY:
      return true;
    default:
      return false;
  }
}

// The units the program in use reads through samplers and images, from its active uniforms.
void command(const char* what) {
  std::set<GLuint> sampler_units, image_units;
  GLint count = 0;
  real.GetProgramiv(program_in_use, GL_ACTIVE_UNIFORMS, &count);
  for (GLint i = 0; i < count; ++i) {
    char name[256];
    GLsizei length = 0;
    GLint size = 0;
    GLenum type = 0;
    get_active_uniform(program_in_use, static_cast<GLuint>(i), sizeof name, &length, &size, &type, name);
    if (!is_sampler(type) && !is_image(type)) continue;
    GLint unit = 0;
    get_uniform_iv(program_in_use, real.GetUniformLocation(program_in_use, name), &unit);
    (is_sampler(type) ? sampler_units : image_units).insert(static_cast<GLuint>(unit));
  }
  record->command(what, sampler_units, image_units);
}

void GL_APIENTRY use_program(GLuint program) {
  program_in_use = program;
  real.UseProgram(program);
}
void GL_APIENTRY active_texture(GLenum unit) {
  active_unit = unit - GL_TEXTURE0;
  real.ActiveTexture(unit);
}
void GL_APIENTRY bind_texture(GLenum target, GLuint texture) {
  if (target == GL_TEXTURE_2D) record->samplers[active_unit] = texture;
  real.BindTexture(target, texture);
}
void GL_APIENTRY bind_image(GLuint unit, GLuint texture, GLint level, GLboolean layered, GLint layer, GLenum access,
                            GLenum format) {
  record->images[unit] = {texture, level, access};
  real.BindImageTexture(unit, texture, level, layered, layer, access, format);
}
void GL_APIENTRY dispatch(GLuint x, GLuint y, GLuint z) {
  command("dispatch");
  real.DispatchCompute(x, y, z);
}
void GL_APIENTRY draw_arrays(GLenum mode, GLint first, GLsizei count) {
  command("draw");
  real.DrawArrays(mode, first, count);
}
void GL_APIENTRY draw_elements(GLenum mode, GLsizei count, GLenum type, const void* indices) {
  command("draw");
  real.DrawElements(mode, count, type, indices);
}
void GL_APIENTRY memory_barrier(GLbitfield bits) {
  record->barrier(bits);
  real.MemoryBarrier(bits);
}

// Routes the calls through the record while it lives. Bindings made before it are unknown to it:
// the passes bind what they read each frame, so after a first frame the record knows them all.
struct Recording {
  Recording(Record& r, const platform::Platform& platform) {
    record = &r;
    real = gl::api;
    get_active_uniform = reinterpret_cast<PFNGLGETACTIVEUNIFORMPROC>(platform.proc_address("glGetActiveUniform"));
    get_uniform_iv = reinterpret_cast<PFNGLGETUNIFORMIVPROC>(platform.proc_address("glGetUniformiv"));
    GLint unit = GL_TEXTURE0, program = 0;
    real.GetIntegerv(GL_ACTIVE_TEXTURE, &unit);
    real.GetIntegerv(GL_CURRENT_PROGRAM, &program);
    active_unit = static_cast<GLenum>(unit) - GL_TEXTURE0;
    program_in_use = static_cast<GLuint>(program);
    gl::api.UseProgram = use_program;
    gl::api.ActiveTexture = active_texture;
    gl::api.BindTexture = bind_texture;
    gl::api.BindImageTexture = bind_image;
    gl::api.DispatchCompute = dispatch;
    gl::api.DrawArrays = draw_arrays;
    gl::api.DrawElements = draw_elements;
    gl::api.MemoryBarrier = memory_barrier;
  }
  ~Recording() {
    gl::api = real;
    record = nullptr;
  }
};

class Barriers : public ::testing::TestWithParam<std::string> {};

TEST_P(Barriers, EveryPassThatReadsAnotherPassesImageStoresWaitsForThem) {
  struct Case {
    ssao::Blur blur;
    bool half_resolution, depth_chain;
  };
  const Case cases[] = {{ssao::Blur::off, false, false},      {ssao::Blur::off, true, false},
                        {ssao::Blur::gaussian, false, false}, {ssao::Blur::gaussian, true, true},
                        {ssao::Blur::bilateral, true, false}, {ssao::Blur::bilateral, false, true},
                        {ssao::Blur::off, true, true}};
  for (const Case& c : cases) {
    render::FrameSettings settings;
    settings.width = settings.height = kSide;
    settings.check_errors = true;
    settings.reuse_static_ao = false;  // every frame runs every pass
    settings.blur.mode = c.blur;
    settings.ao_settings.half_resolution = c.half_resolution;
    settings.ao_settings.depth_chain = c.depth_chain;
    // A radius as wide as the view reads the coarsest levels, so the chain is built when it is on.
    settings.radius = c.depth_chain ? 10.0f : 0.0f;
    const std::string what = std::string("blur ") + std::string(ssao::name(c.blur)) +
                             (c.half_resolution ? ", half resolution" : ", full resolution") +
                             (c.depth_chain ? ", depth chain" : "");
    test::Harness h;
    ASSERT_TRUE(h.start(GetParam(), "builtin:demo", settings)) << what;
    Record r;
    {
      Recording recording(r, *h.platform);
      ASSERT_NE(get_active_uniform, nullptr);
      ASSERT_NE(get_uniform_iv, nullptr);
      // Three frames: the first teaches the record the bindings; the later frames' stores come
      // after the earlier frames' present pass read.
      for (int frame = 0; frame < 3; ++frame) h.renderer.render(h.camera);
    }
    EXPECT_EQ(h.renderer.gl_error(), "") << what;
    // The record must have seen the passes, or an empty record would pass: per frame at least the
    // G-buffer draws, the SSAO dispatch and the present draw, and a barrier after each dispatch.
    EXPECT_GE(r.commands, 3 * 3) << what;
    EXPECT_GE(r.barriers, 3 * 2) << what;
    if (c.depth_chain) {
      EXPECT_GT(r.coarser_level_stores, 0) << what;
    }
    for (const std::string& hazard : r.hazards) ADD_FAILURE() << what << ": " << hazard;
  }
}

// The rules themselves, on hand-made call sequences: a checker that never complains would pass
// the test above.
TEST(BarrierRules, EachHazardIsReportedAndTheRightBitClearsIt) {
  const GLuint ao = 7, blurred = 8;
  auto store = [](Record& r, GLuint texture) {
    r.images[0] = {texture, 0, GL_WRITE_ONLY};
    r.command("dispatch", {}, {0});
  };
  auto sample = [](Record& r, GLuint texture) {
    r.samplers[0] = texture;
    r.command("draw", {0}, {});
  };
  {
    Record r;  // read after write, fetched
    store(r, ao);
    sample(r, ao);
    EXPECT_EQ(r.hazards.size(), 1u);
  }
  {
    Record r;  // the image-access bit does not order fetches
    store(r, ao);
    r.barrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    sample(r, ao);
    EXPECT_EQ(r.hazards.size(), 1u);
  }
  {
    Record r;  // the fetch bit does
    store(r, ao);
    r.barrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    sample(r, ao);
    EXPECT_TRUE(r.hazards.empty());
  }
  {
    Record r;  // read after write, loaded through an image unit
    store(r, ao);
    r.barrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    r.images[1] = {ao, 0, GL_READ_ONLY};
    r.command("dispatch", {}, {1});
    EXPECT_EQ(r.hazards.size(), 1u);
  }
  {
    Record r;  // write after read: only the image-access bit orders the store after the fetch
    sample(r, blurred);
    r.barrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    store(r, blurred);
    EXPECT_EQ(r.hazards.size(), 1u);
    Record s;
    sample(s, blurred);
    s.barrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    store(s, blurred);
    EXPECT_TRUE(s.hazards.empty());
  }
  {
    Record r;  // other textures, and units the program does not use, are not affected
    store(r, ao);
    sample(r, blurred);
    r.samplers[3] = ao;
    r.command("draw", {0}, {});
    EXPECT_TRUE(r.hazards.empty());
  }
  {
    Record r;  // a chain of levels: each samples the texture and stores its next level
    const GLuint depth = 9;
    r.samplers[0] = depth;
    for (GLint level = 1; level <= 3; ++level) {
      r.images[0] = {depth, level, GL_WRITE_ONLY};
      r.command("dispatch", {0}, {0});
      r.barrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    }
    EXPECT_TRUE(r.hazards.empty());
    EXPECT_EQ(r.coarser_level_stores, 3);
    Record unfenced;  // the same chain with the barriers left out
    unfenced.samplers[0] = depth;
    for (GLint level = 1; level <= 3; ++level) {
      unfenced.images[0] = {depth, level, GL_WRITE_ONLY};
      unfenced.command("dispatch", {0}, {0});
    }
    // Level 2's dispatch samples level 1 unfenced; level 3's, levels 1 and 2.
    EXPECT_EQ(unfenced.hazards.size(), 3u);
  }
}

INSTANTIATE_TEST_SUITE_P(Platforms, Barriers, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace
