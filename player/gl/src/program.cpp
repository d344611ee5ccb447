#include "gl/program.h"

#include "gles_shaders/embedded.h"

#include <algorithm>

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

Shader compile(const StageSource& stage, std::string& error) {
  Shader shader(api.CreateShader(stage.type));
  const char* text = stage.text.c_str();
  api.ShaderSource(shader.id(), 1, &text, nullptr);
  api.CompileShader(shader.id());
  GLint ok = GL_FALSE;
  api.GetShaderiv(shader.id(), GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    error = stage.file + " (variant: " + stage.variant + ") failed to compile:\n" + info_log(shader.id(), false);
    return {};
  }
  return shader;
}

}  // namespace

bool stage_sources(std::initializer_list<Stage> stages, const std::string& defines, std::vector<StageSource>& sources,
                   std::string& error) {
  sources.clear();
  for (const Stage& stage : stages) {
    const std::string_view body = gles_shaders::source(stage.file);
    const std::string file = "gles_shaders/" + std::string(stage.file);
    if (body.empty()) {
      error = file + ": no such embedded shader";
      return false;
    }
    // #line keeps the driver's line numbers equal to those of the file (after #include expansion).
    sources.push_back({stage.type, file, defines.empty() ? std::string("default") : defines,
                       "#version 310 es\n" + defines + "#line 1\n" + std::string(body)});
  }
  return true;
}

Program link_program(const std::vector<StageSource>& sources, std::string& error, bool retrievable) {
  std::vector<Shader> shaders;
  for (const StageSource& stage : sources) {
    Shader shader = compile(stage, error);
    if (!shader) return {};
    shaders.push_back(std::move(shader));
  }
  Program program(api.CreateProgram());
  for (const Shader& shader : shaders) api.AttachShader(program.id(), shader.id());
  if (retrievable) api.ProgramParameteri(program.id(), GL_PROGRAM_BINARY_RETRIEVABLE_HINT, GL_TRUE);
  api.LinkProgram(program.id());
  GLint ok = GL_FALSE;
  api.GetProgramiv(program.id(), GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    error = "linking";
    for (const StageSource& stage : sources) error += " " + stage.file;
    error += " failed:\n" + info_log(program.id(), true);
    return {};
  }
  return program;
}

Program build_program(std::initializer_list<Stage> stages, const std::string& defines, std::string& error) {
  std::vector<StageSource> sources;
  if (!stage_sources(stages, defines, sources, error)) return {};
  return link_program(sources, error);
}

GLint uniform(const Program& program, const char* name) {
  return api.GetUniformLocation(program.id(), name);
}

}  // namespace gl
