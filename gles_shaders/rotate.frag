// The frame drawn at the display's logical orientation, turned onto the scanout by a quarter turns
// (board rotation): many boards' display controllers cannot rotate, so the renderer does. Texels are
// copied as they are (texelFetch, no filtering): an sRGB source into an sRGB framebuffer decodes and
// encodes back to the same bytes, a plain one into a plain one is a copy.
precision highp float;
precision highp int;
precision highp sampler2D;

uniform highp sampler2D u_source;
uniform int u_quarter_turns;  // 1: 90 degrees clockwise, 2: 180, 3: 270

layout(location = 0) out vec4 fragment;

void main() {
  ivec2 size = textureSize(u_source, 0);  // the logical frame; the target is it turned
  ivec2 p = ivec2(gl_FragCoord.xy);
  ivec2 source;
  // Clockwise turns of the image as seen, in GL's bottom-up coordinates: the target pixel p of a
  // quarter turn shows the source's (size.x - 1 - p.y, p.x).
  if (u_quarter_turns == 1) source = ivec2(size.x - 1 - p.y, p.x);
  else if (u_quarter_turns == 2) source = ivec2(size.x - 1 - p.x, size.y - 1 - p.y);
  else if (u_quarter_turns == 3) source = ivec2(p.y, size.y - 1 - p.x);
  else source = p;
  fragment = texelFetch(u_source, source, 0);
}
