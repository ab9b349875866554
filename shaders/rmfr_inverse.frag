// RMFR pass 3: each screen pixel of the eye reads the lit reduced buffer, bilinearly, at
// the point the forward mapping sends it to.
#include "common/rmfr.glsl"

layout(binding = 0) uniform sampler2D u_reduced;
uniform ivec2 u_origin;  // the eye's viewport origin in the output
uniform vec2 u_screen_size, u_fovea, u_f;

layout(location = 0) out vec4 o_color;

void main() {
  vec2 p = (gl_FragCoord.xy - vec2(u_origin)) / u_screen_size;
  o_color = texture(u_reduced, rmfr_forward(p, u_fovea, u_f));
}
