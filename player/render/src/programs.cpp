#include "render/programs.h"

#include "gl/program.h"
#include "gl_util.h"
#include "scene/environment.h"

#include <vector>

namespace render {
namespace {

const std::string kMasked = "#define HAS_BASECOLOR_TEXTURE 1\n#define ALPHA_MASK 1\n";

std::string gbuffer_defines(unsigned bits) {
  std::string defines;
  auto define = [&](unsigned bit, const char* name) {
    if (bits & bit) defines += std::string("#define ") + name + " 1\n";
  };
  define(features::base_color_texture, "HAS_BASECOLOR_TEXTURE");
  define(features::alpha_mask, "ALPHA_MASK");
  define(features::metallic_roughness_texture, "HAS_METALLIC_ROUGHNESS_TEXTURE");
  define(features::normal_texture, "HAS_NORMAL_TEXTURE");
  define(features::occlusion_texture, "HAS_OCCLUSION_TEXTURE");
  define(features::emissive_texture, "HAS_EMISSIVE_TEXTURE");
  define(features::metallic_roughness_uv1, "METALLIC_ROUGHNESS_UV1");
  define(features::normal_uv1, "NORMAL_UV1");
  define(features::occlusion_uv1, "OCCLUSION_UV1");
  define(features::emissive_uv1, "EMISSIVE_UV1");
  define(features::skinned, "SKINNED");
  define(features::motion, "MOTION");
  if (bits & (features::metallic_roughness_uv1 | features::normal_uv1 | features::occlusion_uv1 | features::emissive_uv1))
    defines += "#define HAS_UV1 1\n";
  return defines;
}

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
  out.material = gl::uniform(*out.program, "u_material");
  out.emissive = gl::uniform(*out.program, "u_emissive");
  out.frame_handedness = gl::uniform(*out.program, "u_frame_handedness");
  out.joint_base = gl::uniform(*out.program, "u_joint_base");
  out.previous_model_view = gl::uniform(*out.program, "u_previous_model_view");
  gl::api.UseProgram(out.program->id());
  const std::pair<const char*, int> samplers[] = {{"u_base_color_texture", unit_base_color},
                                                  {"u_metallic_roughness_texture", unit_metallic_roughness},
                                                  {"u_normal_texture", unit_normal},
                                                  {"u_occlusion_texture", unit_occlusion},
                                                  {"u_emissive_texture", unit_emissive},
                                                  {"u_specular", unit_specular},
                                                  {"u_brdf_lut", unit_brdf_lut},
                                                  {"u_linear_depth", unit_linear_depth},
                                                  {"u_joint_matrices", unit_joints}};
  for (const auto& [name, unit] : samplers)
    if (const GLint location = gl::uniform(*out.program, name); location >= 0) gl::api.Uniform1i(location, unit);
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
  // The variants every scene of the built-in kind needs; others are compiled when a scene asks.
  if (!prepare_gbuffer(0, false, error) || !prepare_gbuffer(features::base_color_texture, false, error) ||
      !build_raster(cache, depth_only, "depth_only.frag", "", error) ||
      !prepare_gbuffer(features::base_color_texture | features::alpha_mask, false, error) ||
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
      !build_covered_bounds(error))
    return false;
  // The default frame's present programs: its surfaces' rectangle and background, into either kind of
  // framebuffer.
  for (const bool srgb : {true, false})
    for (const PresentDraw draw : {PresentDraw::bounds, PresentDraw::background})
      if (!present(Picture::color, srgb, false, error, draw)) return false;
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

  // The split-sum table: small, and the same for every scene, so made once per context.
  constexpr int kLutSize = 32;
  static const std::vector<glm::vec2> lut = scene::split_sum_lut(kLutSize, 512);
  std::vector<float> texels;
  texels.reserve(lut.size() * 2);
  for (const glm::vec2& entry : lut) texels.insert(texels.end(), {entry.x, entry.y});
  brdf_lut = gl::make_texture();
  gl::api.BindTexture(GL_TEXTURE_2D, brdf_lut.id());
  // Half floats filter everywhere ES 3.0 runs (32-bit ones only with OES_texture_float_linear), and
  // the table needs filtering: its nearest entry of 32 is up to 0.05 off the interpolated value at
  // low roughness, a visible step on a polished sphere; half precision keeps 1e-3 of the [0, 1] range.
  gl::api.TexStorage2D(GL_TEXTURE_2D, 1, GL_RG16F, kLutSize, kLutSize);
  gl::api.TexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, kLutSize, kLutSize, GL_RG, GL_FLOAT, texels.data());
  gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
  gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl::api.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  gl::api.BindTexture(GL_TEXTURE_2D, 0);
  return true;
}

unsigned material_features(const scene::Material& material, bool untextured_variant) {
  unsigned bits = 0;
  if (material.base_color_texture >= 0 || !untextured_variant || material.alpha_tested()) bits |= features::base_color_texture;
  if (material.alpha_tested()) bits |= features::alpha_mask;
  auto slot = [&](const scene::TextureSlot& texture, unsigned bit, unsigned uv1) {
    if (!texture.present()) return;
    bits |= bit;
    if (texture.second_uv) bits |= uv1;
  };
  slot(material.metallic_roughness, features::metallic_roughness_texture, features::metallic_roughness_uv1);
  slot(material.normal, features::normal_texture, features::normal_uv1);
  slot(material.occlusion, features::occlusion_texture, features::occlusion_uv1);
  slot(material.emissive_texture, features::emissive_texture, features::emissive_uv1);
  return bits;
}

bool Programs::prepare_gbuffer(unsigned feature_bits, bool modules, std::string& error) {
  RasterProgram& program = gbuffer_[modules ? 1 : 0][feature_bits];
  if (program.program != nullptr) return true;
  std::string defines = gbuffer_defines(feature_bits);
  if (modules)
    defines += std::string("#define LIGHTFIELD_MODULES 1\n") + (modules_without_material ? "#define NO_MATERIAL_TARGET 1\n" : "");
  if (!build_raster(*cache_, program, "gbuffer.frag", defines, error)) {
    program = RasterProgram{};
    return false;
  }
  gl::api.UseProgram(0);
  return true;
}

bool Programs::build_temporal_motion(std::string& error) {
  if (temporal_motion != nullptr) return true;
  temporal_motion = build_compute(*cache_, "temporal.comp", "#define MOTION 1\n",
                                  {"u_current", "u_normal", "u_history", "u_history_normal", "u_motion"}, error);
  gl::api.UseProgram(0);
  return temporal_motion != nullptr;
}

bool Programs::prepare_skinned_depth(bool modules, std::string& error) {
  std::array<RasterProgram, 2>& programs = skinned_depth_[modules ? 1 : 0];
  if (programs[0].program != nullptr) return true;
  const std::string defines = std::string("#define SKINNED 1\n") + (modules ? "#define LIGHTFIELD_MODULES 1\n" : "");
  if (!build_raster(*cache_, programs[0], "depth_only.frag", defines, error) ||
      !build_raster(*cache_, programs[1], "depth_only.frag", defines + kMasked, error)) {
    programs = {};
    return false;
  }
  gl::api.UseProgram(0);
  return true;
}

bool Programs::prepare_forward(unsigned feature_bits, bool srgb, std::string& error) {
  feature_bits &= features::motion - 1;
  RasterProgram& program = forward_[srgb ? 1 : 0][feature_bits];
  if (program.program != nullptr) return true;
  const std::string defines = gbuffer_defines(feature_bits) + (srgb ? "" : "#define ENCODE_SRGB 1\n");
  if (!build_raster(*cache_, program, "forward.frag", defines, error)) {
    program = RasterProgram{};
    return false;
  }
  gl::api.UseProgram(0);
  return true;
}

const gl::Program* Programs::present(Picture output, bool srgb, bool scene_lights, std::string& error, PresentDraw draw) {
  if (draw == PresentDraw::background) {
    output = Picture::color;
    scene_lights = false;
  }
  const gl::Program*& program =
      present_[static_cast<size_t>(draw)][static_cast<size_t>(output)][srgb ? 1 : 0][scene_lights ? 1 : 0];
  if (program == nullptr) {
    const std::string defines = "#define OUTPUT " + std::to_string(static_cast<int>(output)) + "\n" +
                                (srgb ? "" : "#define ENCODE_SRGB 1\n") + (scene_lights ? "" : "#define NO_SCENE_LIGHTS 1\n") +
                                (draw == PresentDraw::bounds       ? "#define PRESENT_BOUNDS 1\n"
                                 : draw == PresentDraw::background ? "#define BACKGROUND_ONLY 1\n"
                                                                   : "");
    program =
        build_fullscreen(*cache_, "present.frag", defines,
                         {"u_albedo", "u_normal", "u_linear_depth", "u_ao", "u_material", "u_specular", "u_brdf_lut"}, error);
    gl::api.UseProgram(0);
  }
  return program;
}

bool Programs::build_covered_bounds(std::string& error) {
  if (covered_bounds != nullptr) return true;
  covered_bounds = build_compute(
      *cache_, "covered_bounds.comp",
      "#define TILE_SIZE " + std::to_string(kPresentTile) + "\n#define BAND_TILES " + std::to_string(kPresentBandTiles) + "\n",
      {"u_linear_depth"}, error);
  gl::api.UseProgram(0);
  return covered_bounds != nullptr;
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
  if (module_depth_only.program != nullptr) return true;
  GLint draw_buffers = 0;
  gl::api.GetIntegerv(GL_MAX_DRAW_BUFFERS, &draw_buffers);
  modules_without_material = draw_buffers < 5;
  const std::string modules = "#define LIGHTFIELD_MODULES 1\n";
  if (!prepare_gbuffer(0, true, error) || !prepare_gbuffer(features::base_color_texture, true, error) ||
      !build_raster(*cache_, module_depth_only, "depth_only.frag", modules, error) ||
      !prepare_gbuffer(features::base_color_texture | features::alpha_mask, true, error) ||
      !build_raster(*cache_, module_depth_masked, "depth_only.frag", modules + kMasked, error)) {
    module_depth_only = RasterProgram{};
    return false;
  }
  gl::api.UseProgram(0);
  return true;
}

}  // namespace render
