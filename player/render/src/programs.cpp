#include "render/programs.h"

#include "gl/program.h"
#include "gl_util.h"

namespace render {
namespace {

const std::string kMasked = "#define HAS_BASECOLOR_TEXTURE 1\n#define ALPHA_MASK 1\n";

bool build_raster(gl::ProgramCache& cache, RasterProgram& out, const char* fragment, const std::string& defines,
                  std::string& error) {
  out.program = cache.get({{GL_VERTEX_SHADER, "gbuffer.vert"}, {GL_FRAGMENT_SHADER, fragment}}, defines, error);
  if (out.program == nullptr) return false;
  out.model_view = gl::uniform(*out.program, "u_model_view");
  out.projection = gl::uniform(*out.program, "u_projection");
  out.normal_matrix = gl::uniform(*out.program, "u_normal_matrix");
  out.base_color = gl::uniform(*out.program, "u_base_color");
  out.texture = gl::uniform(*out.program, "u_base_color_texture");
  out.alpha_cutoff = gl::uniform(*out.program, "u_alpha_cutoff");
  out.lit = gl::uniform(*out.program, "u_lit");
  return true;
}

// A program of fullscreen.vert and `fragment`, or of the compute shader `file`, with its samplers
// bound to units in the order given.
const gl::Program* build_fullscreen(gl::ProgramCache& cache, const char* fragment, const std::string& defines,
                                    std::initializer_list<const char*> samplers, std::string& error) {
  const gl::Program* program = cache.get({{GL_VERTEX_SHADER, "fullscreen.vert"}, {GL_FRAGMENT_SHADER, fragment}}, defines, error);
  if (program != nullptr) detail::assign_units(*program, samplers);
  return program;
}

const gl::Program* build_compute(gl::ProgramCache& cache, const char* file, const std::string& defines,
                                 std::initializer_list<const char*> samplers, std::string& error) {
  const gl::Program* program = cache.get({{GL_COMPUTE_SHADER, file}}, defines, error);
  if (program != nullptr) detail::assign_units(*program, samplers);
  return program;
}

}  // namespace

bool Programs::build(gl::Session& session, std::string& error) {
  cache_ = &session.programs();
  gl::ProgramCache& cache = *cache_;
  if (!build_raster(cache, gbuffer_plain, "gbuffer.frag", "", error) ||
      !build_raster(cache, gbuffer_textured, "gbuffer.frag", "#define HAS_BASECOLOR_TEXTURE 1\n", error) ||
      !build_raster(cache, depth_only, "depth_only.frag", "", error) ||
      !build_raster(cache, gbuffer_masked, "gbuffer.frag", kMasked, error) ||
      !build_raster(cache, depth_masked, "depth_only.frag", kMasked, error))
    return false;
  if (!(depth_chain = build_compute(cache, "depth_chain.comp", "", {"u_linear_depth"}, error)) ||
      !(upsample = build_compute(cache, "upsample.comp", "", {"u_ao", "u_linear_depth", "u_normal"}, error)) ||
      !(blur_gaussian = build_compute(cache, "blur.comp", "", {"u_source"}, error)) ||
      !(blur_bilateral = build_compute(cache, "blur.comp", "#define BILATERAL 1\n", {"u_source"}, error)) ||
      !(blur_denoise =
            build_compute(cache, "blur.comp", "#define BILATERAL 1\n#define DENOISE 1\n", {"u_source", "u_normal"}, error)) ||
      !(temporal =
            build_compute(cache, "temporal.comp", "", {"u_current", "u_normal", "u_history", "u_history_normal"}, error)) ||
      !present(Picture::color, true, error) || !present(Picture::color, false, error))
    return false;
  depth_chain_source_level = gl::uniform(*depth_chain, "u_source_level");
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

const gl::Program* Programs::present(Picture output, bool srgb, std::string& error) {
  const gl::Program*& program = present_[static_cast<size_t>(output)][srgb ? 1 : 0];
  if (program == nullptr) {
    const std::string defines =
        "#define OUTPUT " + std::to_string(static_cast<int>(output)) + "\n" + (srgb ? "" : "#define ENCODE_SRGB 1\n");
    program = build_fullscreen(*cache_, "present.frag", defines, {"u_albedo", "u_normal", "u_linear_depth", "u_ao"}, error);
    gl::api.UseProgram(0);
  }
  return program;
}

const gl::Program* Programs::ssao(ssao::Estimator estimator, ssao::Precision precision, std::string& error, bool modules) {
  const size_t kind = modules ? 1 : 0;
  const gl::Program*& program = ssao_[kind][index(estimator)][index(precision)];
  if (program == nullptr) {
    if (modules && estimator == ssao::Estimator::horizon) {
      error =
          "estimator: horizon searches screen-space slices and has no light field form; a modules display takes "
          "sphere or hemisphere";
      return nullptr;
    }
    const std::string defines = "#define ESTIMATOR " + std::to_string(static_cast<int>(estimator)) + "\n" +
                                (precision == ssao::Precision::mediump ? "#define AO_MEDIUMP 1\n" : "") +
                                (modules ? "#define LIGHTFIELD_MODULES 1\n" : "");
    program = build_compute(*cache_, "ssao.comp", defines, {"u_linear_depth", "u_normal", "u_positions"}, error);
    if (program == nullptr) return nullptr;
    ssao_inverse_far_[kind][index(estimator)][index(precision)] = gl::uniform(*program, "u_inverse_far");
    ssao_defines_[kind][index(estimator)][index(precision)] = defines;
    gl::api.UseProgram(0);
  }
  return program;
}

bool Programs::build_rotate(std::string& error) {
  if (rotate != nullptr) return true;
  rotate = build_fullscreen(*cache_, "rotate.frag", "", {"u_source"}, error);
  if (rotate == nullptr) return false;
  rotate_quarter_turns = gl::uniform(*rotate, "u_quarter_turns");
  gl::api.UseProgram(0);
  return true;
}

bool Programs::build_interleave(std::string& error) {
  if (interleave != nullptr && decode_copy != nullptr) return true;
  interleave = build_fullscreen(*cache_, "interleave.frag", "", {"u_quilt"}, error);
  decode_copy = interleave ? build_fullscreen(*cache_, "decode_copy.frag", "", {"u_source"}, error) : nullptr;
  if (decode_copy == nullptr) return false;
  interleave_constants = gl::uniform(*interleave, "u_constants");
  interleave_panel = gl::uniform(*interleave, "u_panel");
  interleave_layout = gl::uniform(*interleave, "u_layout");
  decode_copy_rect = gl::uniform(*decode_copy, "u_rect");
  gl::api.UseProgram(0);
  return true;
}

bool Programs::build_module_programs(std::string& error) {
  if (module_gbuffer_plain.program != nullptr) return true;
  const std::string modules = "#define LIGHTFIELD_MODULES 1\n";
  if (!build_raster(*cache_, module_gbuffer_plain, "gbuffer.frag", modules, error) ||
      !build_raster(*cache_, module_gbuffer_textured, "gbuffer.frag", modules + "#define HAS_BASECOLOR_TEXTURE 1\n", error) ||
      !build_raster(*cache_, module_depth_only, "depth_only.frag", modules, error) ||
      !build_raster(*cache_, module_gbuffer_masked, "gbuffer.frag", modules + kMasked, error) ||
      !build_raster(*cache_, module_depth_masked, "depth_only.frag", modules + kMasked, error)) {
    module_gbuffer_plain = RasterProgram{};
    return false;
  }
  gl::api.UseProgram(0);
  return true;
}

}  // namespace render
