#include "gl/program.h"

#include "gles_shaders/embedded.h"

#include <vector>

namespace gl {
namespace {

std::string info_log(GLuint id, bool is_program) {
  GLint length = 0;
  (is_program ? api.GetProgramiv : api.GetShaderiv)(id, GL_INFO_LOG_LENGTH, &length);
  std::string log(static_cast<size_t>(std::max(length, 1)), '\0');
  if (is_program)
    api.GetProgramInfoLog(id, length, nullptr, log.data());
  else
    api.GetShaderInfoLog(id, length, nullptr, log.data());
  while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
  return log;
}

Shader compile(const Stage& stage, const std::string& defines, std::string& error) {
  const std::string_view body = gles_shaders::source(stage.file);
  if (body.empty()) {
    error = "gles_shaders/" + std::string(stage.file) + ": no such embedded shader";
    return {};
  }
  // #line keeps the driver's line numbers equal to those of the file (after #include expansion).
  const std::string text = "#version 310 es\n" + defines + "#line 1\n" + std::string(body);
  Shader shader(api.CreateShader(stage.type));
  const char* source = text.c_str();
  api.ShaderSource(shader.id(), 1, &source, nullptr);
  api.CompileShader(shader.id());
  GLint ok = GL_FALSE;
  api.GetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    error = "gles_shaders/" + std::string(stage.file) + " (variant: " + (defines.empty() ? std::string("default") : defines) +
            ") failed to compile:\n" + info_log(shader.id(), false);
    return {};
  }
  return shader;
}

}  // namespace

Program build_program(std::initializer_list<Stage> stages, const std::string& defines, std::string& error) {
  std::vector<Shader> shaders;
  for (const Stage& stage : stages) {
    Shader shader = compile(stage, defines, error);
    if (!shader) return {};
    shaders.push_back(std::move(shader));
  }
  Program program(api.CreateProgram());
  for (const Shader& shader : shaders) api.AttachShader(program.id(), shader.id());
  api.LinkProgram(program.id());
  GLint ok = GL_FALSE;
  api.GetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    error = "linking";
    for (const Stage& stage : stages) error += " gles_shaders/" + std::string(stage.file);
    error += " failed:\n" + info_log(program.id(), true);
    return {};
  }
  return program;
}

GLint uniform(const Program& program, const char* name) {
  return api.GetUniformLocation(program.id(), name);
}

}  // namespace gl
