// Copies an sRGB-encoded RGBA8 texture into a framebuffer that encodes sRGB itself: decoding first
// makes the framebuffer's encoding give back the same bytes (a blit would encode them twice).
precision highp float;
precision highp int;
precision highp sampler2D;

uniform highp sampler2D u_source;
uniform ivec4 u_rect;  // the destination rectangle: x, y (lower left) and width, height

layout(location = 0) out vec4 fragment;

void main() {
  vec2 uv = (gl_FragCoord.xy - vec2(u_rect.xy)) / vec2(u_rect.zw);
  vec3 c = texture(u_source, uv).rgb;
  fragment = vec4(mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c)), 1.0);
}
