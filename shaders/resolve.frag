// Resolve pass: each screen pixel of the eye reads the lit reduced buffer where the
// method's mapping sends it (bilinear).
#include "common/mapping.glsl"

layout(binding = 0) uniform sampler2D u_reduced;
uniform ivec2 u_origin;  // the eye's viewport origin in the output

layout(location = 0) out vec4 o_color;

void main() { o_color = resolve(u_reduced, gl_FragCoord.xy - vec2(u_origin)); }
