// The lenticular interleave of a Looking Glass style display: each subpixel of the panel shows its
// colour channel of the view its lens sends it to, read from the quilt (view 0 bottom left). The
// math and its derivation from the vendor's calibration: lightfield/quilt.h.
precision highp float;
precision highp int;
precision highp sampler2D;

uniform highp sampler2D u_quilt;
uniform highp vec4 u_constants;  // x: pitch p, y: tilt t, z: subpixel step s, w: center
uniform ivec4 u_panel;           // x, y: panel size; z: 1 when invView; w: 1 when flipImageY
uniform ivec4 u_layout;          // x: quilt columns, y: rows; z, w: view size

layout(location = 0) out vec4 fragment;

void main() {
  ivec2 pixel = ivec2(gl_FragCoord.xy);  // rows counted from the bottom, as the formula counts them
  vec2 uv = (vec2(pixel) + 0.5) / vec2(u_panel.xy);
  int views = u_layout.x * u_layout.y;
  float quilt_v = u_panel.w == 1 ? 1.0 - uv.y : uv.y;
  ivec2 within = min(ivec2(floor(vec2(uv.x, quilt_v) * vec2(u_layout.zw))), u_layout.zw - 1);
  vec3 colour;
  for (int channel = 0; channel < 3; ++channel) {
    float z = fract((uv.x + float(channel) * u_constants.z + uv.y * u_constants.y) * u_constants.x - u_constants.w);
    if (u_panel.z == 1) z = 1.0 - z;
    int view = clamp(int(floor(z * float(views))), 0, views - 1);
    ivec2 tile = ivec2(view % u_layout.x, view / u_layout.x);
    colour[channel] = texelFetch(u_quilt, tile * u_layout.zw + within, 0)[channel];
  }
  fragment = vec4(colour, 1.0);
}
