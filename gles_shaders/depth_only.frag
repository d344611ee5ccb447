// Depth prepass: only the depth buffer is written. ALPHA_MASK: an alpha-tested material cuts the
// same fragments here as in the G-buffer pass (gbuffer.frag), or its holes would keep the prepass's depth.
#ifdef ALPHA_MASK
precision highp float;
in vec2 v_uv;
uniform vec4 u_base_color;
uniform highp sampler2D u_base_color_texture;
uniform float u_alpha_cutoff;
void main() {
  if ((u_base_color * texture(u_base_color_texture, v_uv)).a < u_alpha_cutoff) discard;
}
#else
precision lowp float;
void main() {}
#endif
