// The G-buffer's material target (rg32ui), written by gbuffer.frag and read by present.frag:
//  x: packUnorm4x8(perceptual roughness, metallic, material occlusion, 0)
//  y: emitted radiance (linear, any brightness KHR_materials_emissive_strength gives) in RGB9E5,
//     the shared-exponent format GL has for HDR textures: 9 bits of mantissa per channel, so
//     emissive colours keep about 0.2% precision from 2^-15 to 65408.
// One integer target holds both: a fifth colour target is more than some boards' GPUs draw to
// (VideoCore VI: 4), and an rgba16f one would leave no room for the emission.
#ifndef MATERIAL_GLSL
#define MATERIAL_GLSL

// A cleared texel: rough (1), dielectric (0), unoccluded (1), no emission (x is packUnorm4x8(1, 0, 1, 0)); what a G-buffer pass
// that cannot write the target (light field modules on a 4-target GPU) leaves for present.
#define MATERIAL_CLEAR_X 0x00FF00FFu

highp uint pack_rgb9e5(highp vec3 rgb) {
  const highp float max_value = 65408.0;  // (511 / 512) * 2^16
  highp vec3 c = clamp(rgb, vec3(0.0), vec3(max_value));
  highp float largest = max(c.r, max(c.g, c.b));
  if (largest < 1.0 / 32768.0) return 0u;
  highp int exponent = max(-16, int(floor(log2(largest)))) + 16;  // biased by 15, + 1
  highp float scale = exp2(float(exponent - 15 - 9));
  if (floor(largest / scale + 0.5) >= 512.0) {
    scale *= 2.0;
    exponent += 1;
  }
  highp uvec3 m = uvec3(min(floor(c / scale + 0.5), vec3(511.0)));
  return m.r | (m.g << 9) | (m.b << 18) | (uint(exponent) << 27);
}

highp vec3 unpack_rgb9e5(highp uint bits) {
  highp float scale = exp2(float(int(bits >> 27) - 15 - 9));
  return vec3(float(bits & 511u), float((bits >> 9) & 511u), float((bits >> 18) & 511u)) * scale;
}

#endif
