#pragma once
// Every compiled program the passes use, built once per context. SSAO variants (one per estimator)
// are compiled on first use and kept.
#include "gl/caps.h"
#include "gl/objects.h"
#include "render/settings.h"
#include "ssao/sampling.h"

#include <array>
#include <string>

namespace render {

struct RasterProgram {
  gl::Program program;
  GLint model_view = -1, projection = -1, normal_matrix = -1, base_color = -1, texture = -1;
};

class Programs {
 public:
  // Returns false and says why (the file, the variant and the driver's log).
  bool build(const gl::Caps& caps, std::string& error);
  // The SSAO program for `estimator`, compiled now if it was not yet; null and `error` on failure.
  const gl::Program* ssao(ssao::Estimator estimator, std::string& error);
  GLint ssao_inverse_far(ssao::Estimator estimator) const { return ssao_inverse_far_[index(estimator)]; }

  RasterProgram gbuffer_plain, gbuffer_textured, depth_only;
  gl::Program depth_chain, blur_gaussian, blur_bilateral, upsample;
  GLint depth_chain_source_level = -1;
  // The present pass for `output`, into a framebuffer that encodes sRGB itself (`srgb`) or not.
  // The shaded image's two are built by build(); the debug outputs' on first use.
  const gl::Program* present(Output output, bool srgb, std::string& error);
  gl::VertexArray empty_vertex_array;  // the present pass has no attributes; core GL still wants a VAO
  gl::Texture white;  // stands in for a missing base colour texture when untextured_variant is off

 private:
  static size_t index(ssao::Estimator estimator) { return static_cast<size_t>(estimator); }
  std::array<gl::Program, 3> ssao_{};
  std::array<std::array<gl::Program, 2>, std::size(kOutputNames)> present_{};
  std::array<GLint, 3> ssao_inverse_far_{-1, -1, -1};
};

}  // namespace render
