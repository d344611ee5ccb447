#pragma once
// CPU reference of the AO passes: the same algorithms as depth_chain.comp, ssao.comp, blur.comp and
// upsample.comp, step for step, in 32-bit floats, rounding to half floats where the GPU stores
// rgba16f. Tests compare the GPU with it.
#include "gles_shaders/shared_layout.h"
#include "ssao/params.h"
#include "ssao/sampling.h"

#include <vector>

namespace ssao {

// One pixel of the AO images: x = AO, y = linear depth / far (0 for background).
using AoTexel = glm::vec2;

// A full-resolution image and its coarser levels, row 0 at the bottom (GL order), 0 for background.
struct DepthChain {
  std::vector<std::vector<float>> levels;
  std::vector<glm::ivec2> sizes;
  float at(glm::ivec2 texel, int level) const;
};
DepthChain build_depth_chain(const std::vector<float>& linear_depth, int width, int height);

// AO at the AO resolution of `params` (full or half). `view_normals` are the G-buffer's view-space
// shading normals at full resolution (used by the hemisphere and horizon estimators), empty for +z;
// `view_face_normals` the faces' geometric normals (the horizon's), empty for the shading normals.
// `mediump` emulates the AO_MEDIUMP variant (--precision mediump) of every estimator by rounding what
// ssao.comp declares SAMPLE_PRECISION (per-sample offsets and depth differences, per-tap offsets and
// horizons) to half floats.
std::vector<AoTexel> reference_ssao(const DepthChain& depth, const std::vector<glm::vec3>& view_normals,
                                    const std::vector<glm::vec3>& view_face_normals, const shared_layout::SsaoParams& params,
                                    float inverse_far, Estimator estimator, bool mediump = false);
// `mode` gaussian, bilateral or denoise; denoise reads `view_normals` (full resolution, as for
// reference_ssao) at each AO texel's full-resolution pixel.
std::vector<AoTexel> reference_blur(const std::vector<AoTexel>& source, const shared_layout::BlurParams& params, Blur mode,
                                    const std::vector<glm::vec3>& view_normals = {}, int full_width = 0);
// upsample.glsl: `low` supplies the AO (x); each texel's depth is `linear_depth` (full resolution,
// times UpsampleParams.inverse_far) at the pixel it shaded. `view_normals` (full resolution, view
// space): the pixels' tangent planes for the plane weights (UpsampleParams.plane_tolerance); empty weighs by
// depth alone.
std::vector<AoTexel> reference_upsample(const std::vector<AoTexel>& low, const std::vector<float>& linear_depth,
                                        const shared_layout::UpsampleParams& params,
                                        const std::vector<glm::vec3>& view_normals = {});

}  // namespace ssao
