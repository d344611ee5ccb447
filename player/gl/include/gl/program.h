#pragma once
// Programs from the embedded GLSL ES 3.10 sources, with variants chosen by prepended #defines.
#include "gl/objects.h"

#include <initializer_list>
#include <string>
#include <string_view>

namespace gl {

struct Stage {
  GLenum type;            // GL_VERTEX_SHADER, GL_FRAGMENT_SHADER or GL_COMPUTE_SHADER
  std::string_view file;  // a file name in gles_shaders/, e.g. "ssao.comp"
};

// Compiles and links the stages. `defines` holds whole "#define NAME VALUE\n" lines. On failure
// returns an empty Program and puts the file, the variant and the driver's log in `error`.
Program build_program(std::initializer_list<Stage> stages, const std::string& defines, std::string& error);

GLint uniform(const Program& program, const char* name);

}  // namespace gl
