// Precision and helpers shared by the compute passes.
// highp by default in every variant: AO_MEDIUMP (ssao.comp's SAMPLE_PRECISION) lowers only what it
// names. A mediump default also made the uniform blocks' members mediump, and llvmpipe ran arithmetic
// on them at 16 bits (the horizon's unprojection from them moved the AO by 0.005).
precision highp float;
precision highp int;
precision highp sampler2D;
precision highp image2D;

// The view-space position of full-resolution `pixel` (centre) at linear `depth`, for a projection
// whose `unproject` is (1/P00, 1/P11, P20, P21), as SsaoParams.unproject holds it, on an image of `size`.
highp vec3 view_position_at(ivec2 pixel, highp float depth, highp vec4 unproject, ivec2 size) {
  highp vec2 ndc = (vec2(pixel) + 0.5) / vec2(size) * 2.0 - 1.0;
  return vec3((ndc + unproject.zw) * depth * unproject.xy, -depth);
}
