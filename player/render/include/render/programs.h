#pragma once
// Every program the passes use, by name, with its uniform locations. The programs themselves are the
// session's (gl/session.h): compiled once per context and shared by every Programs of that context.
// SSAO variants (one per estimator, precision and view kind) and the light field modules' G-buffer
// programs are compiled on first use.
#include "gl/objects.h"
#include "gl/session.h"
#include "render/settings.h"
#include "scene/scene.h"
#include "ssao/sampling.h"

#include <array>
#include <string>

namespace render {

struct RasterProgram {
  const gl::Program* program = nullptr;
  GLint model_view = -1, projection = -1, normal_matrix = -1, base_color = -1, texture = -1, alpha_cutoff = -1, lit = -1;
  GLint material = -1, emissive = -1, frame_handedness = -1;
  GLint joint_base = -1;           // SKINNED: the draw's first row of the joint matrices texture
  GLint previous_model_view = -1;  // MOTION: the previous pose's model, through this frame's view
};

// What a material asks of the G-buffer program (gbuffer.frag's variants), as bits.
namespace features {
constexpr unsigned base_color_texture = 1u << 0;
constexpr unsigned alpha_mask = 1u << 1;
constexpr unsigned metallic_roughness_texture = 1u << 2;
constexpr unsigned normal_texture = 1u << 3;
constexpr unsigned occlusion_texture = 1u << 4;
constexpr unsigned emissive_texture = 1u << 5;
// Which of those textures read the second UV mapping.
constexpr unsigned metallic_roughness_uv1 = 1u << 6;
constexpr unsigned normal_uv1 = 1u << 7;
constexpr unsigned occlusion_uv1 = 1u << 8;
constexpr unsigned emissive_uv1 = 1u << 9;
// Not a material's: a skinned draw's vertices are moved by its joints (SKINNED).
constexpr unsigned skinned = 1u << 10;
// Nor this: the G-buffer writes each pixel's motion since the previous pose (MOTION), for an
// animated scene's temporal AO.
constexpr unsigned motion = 1u << 11;
constexpr unsigned count = 1u << 12;
}  // namespace features

// The feature bits of `material`; `untextured_variant` off: untextured materials fetch a white texel.
unsigned material_features(const scene::Material& material, bool untextured_variant);
// Texture units of the G-buffer programs' samplers, and the forward programs' besides.
enum TextureUnit {
  unit_base_color = 0,
  unit_metallic_roughness,
  unit_normal,
  unit_occlusion,
  unit_emissive,
  unit_specular,
  unit_brdf_lut,
  unit_linear_depth,
  unit_joints
};

// How the present pass covers its view (Programs::present).
enum class PresentDraw { fullscreen, bounds, background };

class Programs {
 public:
  // Builds what every frame needs (or finds it in the session). Returns false and says why (the file,
  // the variant and the driver's log). The session outlives this object.
  bool build(gl::Session& session, std::string& error);
  // The SSAO program for `estimator` at `precision` (mediump: the AO_MEDIUMP variant), compiled now if
  // it was not yet; null and `error` on failure.
  // `modules`: Algorithm 2 for a light field display's optical module (LIGHTFIELD_MODULES); the
  // horizon estimator has no such form and fails with a message saying so.
  const gl::Program* ssao(ssao::Estimator estimator, ssao::Precision precision, std::string& error, bool modules = false);
  GLint ssao_inverse_far(ssao::Estimator estimator, ssao::Precision precision, bool modules = false) const {
    return ssao_inverse_far_[modules ? 1 : 0][index(estimator)][index(precision)];
  }
  // The #defines that variant was compiled with (empty before it was): what really selects it.
  std::string_view ssao_defines(ssao::Estimator estimator, ssao::Precision precision, bool modules = false) const {
    return ssao_defines_[modules ? 1 : 0][index(estimator)][index(precision)];
  }
  // The G-buffer and prepass programs of light field modules (world-to-image per vertex, positions
  // texture), compiled on first call.
  bool build_module_programs(std::string& error);
  // The lenticular interleave of quilt displays (interleave.frag), compiled on first call.
  bool build_interleave(std::string& error);
  const gl::Program* interleave = nullptr;
  GLint interleave_constants = -1, interleave_panel = -1, interleave_layout = -1;
  // An sRGB-encoded texture into a framebuffer that encodes itself (decode_copy.frag), built with it.
  const gl::Program* decode_copy = nullptr;
  GLint decode_copy_rect = -1;
  // A frame turned by quarter turns onto the surface (rotate.frag, see render/rotation.h), compiled on first call.
  bool build_rotate(std::string& error);
  const gl::Program* rotate = nullptr;
  GLint rotate_quarter_turns = -1;

  // The G-buffer program of a feature set (features::), compiled by prepare_gbuffer; null before.
  const RasterProgram* gbuffer(unsigned feature_bits, bool modules) const {
    const RasterProgram& program = gbuffer_[modules ? 1 : 0][feature_bits];
    return program.program ? &program : nullptr;
  }
  // Compiles the variant of `feature_bits` (for light field modules: `modules`) unless it exists.
  bool prepare_gbuffer(unsigned feature_bits, bool modules, std::string& error);
  // The forward program of blended materials (forward.frag) of a feature set (without alpha_mask),
  // into a framebuffer that encodes sRGB itself (`srgb`) or not; null before prepare_forward.
  const RasterProgram* forward(unsigned feature_bits, bool srgb) const {
    const RasterProgram& program = forward_[srgb ? 1 : 0][feature_bits & (features::motion - 1)];
    return program.program ? &program : nullptr;
  }
  bool prepare_forward(unsigned feature_bits, bool srgb, std::string& error);
  RasterProgram depth_only, depth_masked;  // alpha-tested materials (scene::Material::alpha_tested)
  // The prepass programs of skinned draws (for light field modules: `modules`), compiled by
  // prepare_skinned_depth; null before.
  const RasterProgram* skinned_depth(bool masked, bool modules) const {
    const RasterProgram& program = skinned_depth_[modules ? 1 : 0][masked ? 1 : 0];
    return program.program ? &program : nullptr;
  }
  bool prepare_skinned_depth(bool modules, std::string& error);
  RasterProgram module_depth_only, module_depth_masked;  // see build_module_programs
  // Light field modules cannot write the material target (a GPU with four draw buffers).
  bool modules_without_material = false;
  // The split-sum table of the present pass (scene::split_sum_lut), made with the programs.
  gl::Texture brdf_lut;
  const gl::Program *depth_chain = nullptr, *blur_gaussian = nullptr, *blur_bilateral = nullptr, *blur_denoise = nullptr,
                    *upsample = nullptr, *temporal = nullptr;
  // The temporal pass that reads the G-buffer's motion target (features::motion), compiled on first call.
  bool build_temporal_motion(std::string& error);
  const gl::Program* temporal_motion = nullptr;
  GLint depth_chain_source_level = -1;
  // The present pass for `output`, into a framebuffer that encodes sRGB itself (`srgb`) or not,
  // for a scene with lights of its own (`scene_lights`) or none (NO_SCENE_LIGHTS: llvmpipe paid 5 of
  // 36 ms at 1024x768 for the loop over no lights). The shaded image's for a scene without lights
  // are built by build(); the others on first use.
  // `draw`: over the whole view (fullscreen.vert's one triangle), over the rectangle of
  // covered_bounds.comp (PRESENT_BOUNDS), or the background alone (BACKGROUND_ONLY, whose output and
  // lights make no difference: the color variant without lights stands for all).
  const gl::Program* present(Picture output, bool srgb, bool scene_lights, std::string& error,
                             PresentDraw draw = PresentDraw::fullscreen);
  // covered_bounds.comp (the rectangle of tiles of kPresentTile pixels that holds the view's
  // surfaces), compiled on first call.
  bool build_covered_bounds(std::string& error);
  const gl::Program* covered_bounds = nullptr;
  static constexpr int kPresentTile = 16, kPresentBandTiles = 8;  // bands of 128 pixels
  gl::VertexArray empty_vertex_array;                             // the present pass has no attributes; core GL still wants a VAO
  gl::Texture white;  // stands in for a missing base colour texture when untextured_variant is off

 private:
  gl::ProgramCache* cache_ = nullptr;
  static size_t index(ssao::Estimator estimator) { return static_cast<size_t>(estimator); }
  static size_t index(ssao::Precision precision) { return static_cast<size_t>(precision); }
  template <typename T>
  using PerVariant = std::array<std::array<std::array<T, std::size(ssao::kPrecisions)>, std::size(ssao::kEstimators)>, 2>;
  PerVariant<const gl::Program*> ssao_{};
  std::array<std::array<std::array<std::array<const gl::Program*, 2>, 2>, std::size(kPictureNames)>, 3> present_{};
  std::array<std::array<RasterProgram, features::count>, 2> gbuffer_{};
  std::array<std::array<RasterProgram, features::motion>, 2> forward_{};  // blended draws write no motion
  std::array<std::array<RasterProgram, 2>, 2> skinned_depth_{};
  PerVariant<std::string> ssao_defines_{};
  PerVariant<GLint> ssao_inverse_far_{};
};

}  // namespace render
