// The owners of GL object names: each deletes its object once, when it is destroyed, reset or
// assigned over; a moved-from owner holds nothing and deletes nothing, so the object lives on in its
// new owner. Seen through the driver's own glIs* queries.
#include "harness.h"

#include "gl/objects.h"

#include <gtest/gtest.h>

#include <functional>

namespace {

using IsObject = GLboolean (*)(GLuint);

class GlObjects : public ::testing::TestWithParam<std::string> {
 protected:
  void SetUp() override {
    std::string error;
    session_ = test::open_session(GetParam(), 64, 48, error);
    ASSERT_TRUE(session_) << error;
  }
  IsObject is(const char* name) const {
    auto function = reinterpret_cast<IsObject>(session_->platform().proc_address(name));
    EXPECT_NE(function, nullptr) << name;
    return function;
  }

  // The life of one kind of owner: `make` gives a fresh owner whose object exists (bound once where
  // GL makes the object only then); `alive` asks the driver whether a name is an object.
  template <typename Owner>
  void expect_owned(const std::function<Owner()>& make, IsObject alive) {
    ASSERT_NE(alive, nullptr);
    GLuint first = 0, second = 0;
    {
      Owner owner = make();
      first = owner.id();
      ASSERT_NE(first, 0u);
      EXPECT_TRUE(owner);
      EXPECT_TRUE(alive(first));
      Owner moved(std::move(owner));
      EXPECT_FALSE(owner) << "a moved-from owner holds nothing";
      EXPECT_EQ(owner.id(), 0u);
      EXPECT_EQ(moved.id(), first);
      EXPECT_TRUE(alive(first)) << "moving deletes nothing";
      Owner assigned;
      assigned = std::move(moved);
      EXPECT_FALSE(moved);
      EXPECT_EQ(assigned.id(), first);
      EXPECT_TRUE(alive(first));
      Owner& same = assigned;
      assigned = std::move(same);  // onto itself: kept
      EXPECT_EQ(assigned.id(), first);
      EXPECT_TRUE(alive(first));
      assigned = make();  // assigned over: the old object goes
      second = assigned.id();
      EXPECT_NE(second, first);
      EXPECT_FALSE(alive(first));
      EXPECT_TRUE(alive(second));
    }
    EXPECT_FALSE(alive(second)) << "destroyed with its owner";
    Owner reset = make();
    const GLuint third = reset.id();
    reset.reset();
    EXPECT_FALSE(reset);
    EXPECT_FALSE(alive(third));
    reset.reset();  // nothing left to delete
    EXPECT_FALSE(reset);
    EXPECT_EQ(gl::api.GetError(), static_cast<GLenum>(GL_NO_ERROR));
  }

  std::unique_ptr<gl::Session> session_;
};

TEST_P(GlObjects, EachOwnerDeletesItsObjectOnceAndAMovedFromOwnerNothing) {
  expect_owned<gl::Buffer>(
      [] {
        gl::Buffer buffer = gl::make_buffer();
        gl::api.BindBuffer(GL_ARRAY_BUFFER, buffer.id());
        gl::api.BindBuffer(GL_ARRAY_BUFFER, 0);
        return buffer;
      },
      is("glIsBuffer"));
  expect_owned<gl::Texture>(
      [] {
        gl::Texture texture = gl::make_texture();
        gl::api.BindTexture(GL_TEXTURE_2D, texture.id());
        gl::api.BindTexture(GL_TEXTURE_2D, 0);
        return texture;
      },
      is("glIsTexture"));
  expect_owned<gl::Framebuffer>(
      [this] {
        gl::Framebuffer framebuffer = gl::make_framebuffer();
        gl::api.BindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
        gl::api.BindFramebuffer(GL_FRAMEBUFFER, session_->platform().framebuffer());
        return framebuffer;
      },
      is("glIsFramebuffer"));
  expect_owned<gl::VertexArray>(
      [] {
        gl::VertexArray array = gl::make_vertex_array();
        gl::api.BindVertexArray(array.id());
        gl::api.BindVertexArray(0);
        return array;
      },
      is("glIsVertexArray"));
  expect_owned<gl::Program>([] { return gl::Program(gl::api.CreateProgram()); }, is("glIsProgram"));
  expect_owned<gl::Shader>([] { return gl::Shader(gl::api.CreateShader(GL_FRAGMENT_SHADER)); }, is("glIsShader"));
  if (session_->caps().timer_query) {
    // A query name is an object once it has been used.
    IsObject is_query = is("glIsQuery");
    if (is_query == nullptr) is_query = is("glIsQueryEXT");
    expect_owned<gl::Query>(
        [] {
          gl::Query query = gl::make_query();
          gl::api.QueryCounter(query.id(), GL_TIMESTAMP_EXT);
          return query;
        },
        is_query);
  }
}

INSTANTIATE_TEST_SUITE_P(Platforms, GlObjects, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace
