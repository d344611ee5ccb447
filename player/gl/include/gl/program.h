#pragma once
// Programs from the embedded GLSL ES 3.10 sources, with variants chosen by prepended #defines.
#include "gl/objects.h"

#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

namespace gl {

struct Stage {
  GLenum type;            // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER or GL_COMPUTE_SHADER
  std::string_view file;  // a file name in gles_shaders/, e.g. "ssao.comp"
};

// One stage's whole text as the driver gets it: what a program binary is keyed by.
struct StageSource {
  GLenum type;
  std::string file;     // for messages: "gles_shaders/ssao.comp", or a test's name
  std::string variant;  // for messages: the defines, or "default"
  std::string text;
};

// The texts of `stages` with `defines` (whole "#define NAME VALUE\n" lines) put after the #version
// line. False, naming the file, when a stage is not embedded.
bool stage_sources(std::initializer_list<Stage> stages, const std::string& defines, std::vector<StageSource>& sources,
                   std::string& error);

// Compiles and links. With `retrievable`, the driver is told that the binary will be read back
// (GL_PROGRAM_BINARY_RETRIEVABLE_HINT). On failure returns an empty Program and puts the file, the
// variant and the driver's log in `error`.
Program link_program(const std::vector<StageSource>& sources, std::string& error, bool retrievable = false);

// stage_sources and link_program in one.
Program build_program(std::initializer_list<Stage> stages, const std::string& defines, std::string& error);

GLint uniform(const Program& program, const char* name);

}  // namespace gl
