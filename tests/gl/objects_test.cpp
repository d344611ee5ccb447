// The owners of GL object names: each deletes its object once, when it is destroyed, reset or
// assigned over; a moved-from owner holds nothing and deletes nothing, so the object lives on in its
// new owner. Seen through the driver's own glIs* queries.
#include "harness.h"

#include "gl/objects.h"

#include <gtest/gtest.h>

#include <functional>

namespace {

using IsObject = GLboolean (*)(GLuint);

class GlObjects : public test::SessionTest {
 protected:
  IsObject is(const char* name) const {
    auto function = reinterpret_cast<IsObject>(session_->platform().proc_address(name));
    EXPECT_NE(function, nullptr) << name;
    return function;
  }

  // The life of one kind of owner: `make` gives a fresh owner, `use` makes its name an object where
  // GL makes the object only when it is first bound or used, and `alive` asks the driver whether a
  // name is an object.
  template <typename Owner>
  void expect_owned(Owner (*make)(), const std::function<void(GLuint)>& use, IsObject alive) {
    ASSERT_NE(alive, nullptr);
    const auto made = [&] {
      Owner owner = make();
      use(owner.id());
      return owner;
    };
    GLuint first = 0, second = 0;
    {
      Owner owner = made();
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
      assigned = made();  // assigned over: the old object goes
      second = assigned.id();
      EXPECT_NE(second, first);
      EXPECT_FALSE(alive(first));
      EXPECT_TRUE(alive(second));
    }
    EXPECT_FALSE(alive(second)) << "destroyed with its owner";
    Owner reset = made();
    const GLuint third = reset.id();
    reset.reset();
    EXPECT_FALSE(reset);
    EXPECT_FALSE(alive(third));
    reset.reset();  // nothing left to delete
    EXPECT_FALSE(reset);
    EXPECT_EQ(gl::api.GetError(), static_cast<GLenum>(GL_NO_ERROR));
  }
};

gl::Program create_program() {
  return gl::Program(gl::api.CreateProgram());
}
gl::Shader create_shader() {
  return gl::Shader(gl::api.CreateShader(GL_FRAGMENT_SHADER));
}
void created(GLuint) {}

TEST_P(GlObjects, EachOwnerDeletesItsObjectOnceAndAMovedFromOwnerNothing) {
  expect_owned(
      gl::make_buffer,
      [](GLuint id) {
        gl::api.BindBuffer(GL_ARRAY_BUFFER, id);
        gl::api.BindBuffer(GL_ARRAY_BUFFER, 0);
      },
      is("glIsBuffer"));
  expect_owned(
      gl::make_texture,
      [](GLuint id) {
        gl::api.BindTexture(GL_TEXTURE_2D, id);
        gl::api.BindTexture(GL_TEXTURE_2D, 0);
      },
      is("glIsTexture"));
  expect_owned(
      gl::make_framebuffer,
      [this](GLuint id) {
        gl::api.BindFramebuffer(GL_FRAMEBUFFER, id);
        gl::api.BindFramebuffer(GL_FRAMEBUFFER, session_->platform().framebuffer());
      },
      is("glIsFramebuffer"));
  expect_owned(
      gl::make_vertex_array,
      [](GLuint id) {
        gl::api.BindVertexArray(id);
        gl::api.BindVertexArray(0);
      },
      is("glIsVertexArray"));
  expect_owned(create_program, created, is("glIsProgram"));
  expect_owned(create_shader, created, is("glIsShader"));
  if (session_->caps().timer_query) {
    // A query name is an object once it has been used.
    IsObject is_query = is("glIsQuery");
    if (is_query == nullptr) is_query = is("glIsQueryEXT");
    expect_owned(
        gl::make_query, [](GLuint id) { gl::api.QueryCounter(id, GL_TIMESTAMP_EXT); }, is_query);
  }
}

INSTANTIATE_TEST_SUITE_P(Platforms, GlObjects, ::testing::Values("egl", "osmesa"), test::platform_name);

}  // namespace
