#include "render/programs.h"

#include "gl/program.h"
#include "gl_util.h"

namespace render {
namespace {

bool build_raster(RasterProgram& out, const char* fragment, const std::string& defines, std::string& error) {
  out.program = gl::build_program({{GL_VERTEX_SHADER, "gbuffer.vert"}, {GL_FRAGMENT_SHADER, fragment}}, defines, error);
  if (!out.program) return false;
  out.model_view = gl::uniform(out.program, "u_model_view");
  out.projection = gl::uniform(out.program, "u_projection");
  out.normal_matrix = gl::uniform(out.program, "u_normal_matrix");
  out.base_color = gl::uniform(out.program, "u_base_color");
  out.texture = gl::uniform(out.program, "u_base_color_texture");
  return true;
}

bool build_compute(gl::Program& out, const char* file, const std::string& defines, std::string& error) {
  out = gl::build_program({{GL_COMPUTE_SHADER, file}}, defines, error);
  return static_cast<bool>(out);
}

bool build_present(gl::Program& out, const std::string& defines, std::string& error) {
  out = gl::build_program({{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "present.frag"}}, defines, error);
  if (!out) return false;
  detail::assign_units(out, {"u_albedo", "u_normal", "u_linear_depth", "u_ao"});
  return true;
}

}  // namespace

bool Programs::build(const gl::Caps&, std::string& error) {
  if (!build_raster(gbuffer_plain, "gbuffer.frag", "", error) ||
      !build_raster(gbuffer_textured, "gbuffer.frag", "#define HAS_BASECOLOR_TEXTURE 1\n", error) ||
      !build_raster(depth_only, "depth_only.frag", "", error) || !build_compute(depth_chain, "depth_chain.comp", "", error) ||
      !build_compute(upsample, "upsample.comp", "", error) || !build_compute(blur_gaussian, "blur.comp", "", error) ||
      !build_compute(blur_bilateral, "blur.comp", "#define BILATERAL 1\n", error) ||
      !build_compute(blur_denoise, "blur.comp", "#define BILATERAL 1\n#define DENOISE 1\n", error) ||
      !build_compute(temporal, "temporal.comp", "", error) || !present(Output::color, true, error) || !present(Output::color, false, error))
    return false;
  depth_chain_source_level = gl::uniform(depth_chain, "u_source_level");
  detail::assign_units(depth_chain, {"u_linear_depth"});
  detail::assign_units(upsample, {"u_ao", "u_linear_depth", "u_normal"});
  detail::assign_units(blur_gaussian, {"u_source"});
  detail::assign_units(blur_bilateral, {"u_source"});
  detail::assign_units(blur_denoise, {"u_source", "u_normal"});
  detail::assign_units(temporal, {"u_current", "u_normal", "u_history", "u_history_normal"});
  gl::api.UseProgram(0);
  empty_vertex_array = gl::make_vertex_array();

  white = gl::make_texture();
  gl::api.BindTexture(GL_TEXTURE_2D, white.id());
  gl::api.TexStorage2D(GL_TEXTURE_2D, 1, GL_SRGB8_ALPHA8, 1, 1);
  const uint8_t white_texel[4] = {255, 255, 255, 255};
  gl::api.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl::api.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, white_texel);
  gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl::api.BindTexture(GL_TEXTURE_2D, 0);
  return true;
}

const gl::Program* Programs::present(Output output, bool srgb, std::string& error) {
  gl::Program& program = present_[static_cast<size_t>(output)][srgb ? 1 : 0];
  if (!program) {
    const std::string defines = "#define OUTPUT " + std::to_string(static_cast<int>(output)) + "\n" +
                                (srgb ? "" : "#define ENCODE_SRGB 1\n");
    if (!build_present(program, defines, error)) return nullptr;
    gl::api.UseProgram(0);
  }
  return &program;
}

const gl::Program* Programs::ssao(ssao::Estimator estimator, ssao::Precision precision, std::string& error, bool modules) {
  const size_t kind = modules ? 1 : 0;
  gl::Program& program = ssao_[kind][index(estimator)][index(precision)];
  if (!program) {
    if (modules && estimator == ssao::Estimator::horizon) {
      error = "estimator: horizon searches screen-space slices and has no light field form; a modules display takes "
              "sphere or hemisphere";
      return nullptr;
    }
    const std::string defines = "#define ESTIMATOR " + std::to_string(static_cast<int>(estimator)) + "\n" +
                                (precision == ssao::Precision::mediump ? "#define AO_MEDIUMP 1\n" : "") +
                                (modules ? "#define LIGHTFIELD_MODULES 1\n" : "");
    if (!build_compute(program, "ssao.comp", defines, error)) return nullptr;
    ssao_inverse_far_[kind][index(estimator)][index(precision)] = gl::uniform(program, "u_inverse_far");
    ssao_defines_[kind][index(estimator)][index(precision)] = defines;
    detail::assign_units(program, {"u_linear_depth", "u_normal", "u_positions"});
    gl::api.UseProgram(0);
  }
  return &program;
}

bool Programs::build_rotate(std::string& error) {
  if (rotate) return true;
  rotate = gl::build_program({{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "rotate.frag"}}, "", error);
  if (!rotate) return false;
  detail::assign_units(rotate, {"u_source"});
  rotate_quarter_turns = gl::uniform(rotate, "u_quarter_turns");
  gl::api.UseProgram(0);
  return true;
}

bool Programs::build_interleave(std::string& error) {
  if (interleave) return true;
  interleave = gl::build_program({{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "interleave.frag"}}, "", error);
  if (!interleave) return false;
  detail::assign_units(interleave, {"u_quilt"});
  interleave_constants = gl::uniform(interleave, "u_constants");
  interleave_panel = gl::uniform(interleave, "u_panel");
  interleave_layout = gl::uniform(interleave, "u_layout");
  decode_copy = gl::build_program({{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, "decode_copy.frag"}}, "", error);
  if (!decode_copy) return false;
  detail::assign_units(decode_copy, {"u_source"});
  decode_copy_rect = gl::uniform(decode_copy, "u_rect");
  gl::api.UseProgram(0);
  return true;
}

bool Programs::build_module_programs(std::string& error) {
  if (module_gbuffer_plain.program) return true;
  const std::string modules = "#define LIGHTFIELD_MODULES 1\n";
  if (!build_raster(module_gbuffer_plain, "gbuffer.frag", modules, error) ||
      !build_raster(module_gbuffer_textured, "gbuffer.frag", modules + "#define HAS_BASECOLOR_TEXTURE 1\n", error) ||
      !build_raster(module_depth_only, "depth_only.frag", modules, error)) {
    module_gbuffer_plain = RasterProgram{};
    return false;
  }
  gl::api.UseProgram(0);
  return true;
}

}  // namespace render
