// Resolve pass of every method but RMFR's kernel (whose resolve is foveal-rmfr's): each screen
// pixel of the eye reads the lit reduced buffer where the method's mapping sends it
// (bilinear). With lens distortion, each colour channel reads
// where the lens model says (docs/display-model.md): the correction is folded into this
// pass, so the corrected image costs no extra full-resolution pass.
#include "common/mapping.glsl"

layout(binding = 0) uniform sampler2D u_reduced;
uniform ivec2 u_origin;  // the eye's viewport origin in the output
// With DISTORTION defined (a separate program):
uniform vec2 u_lens_center;  // GL frame, normalised
uniform vec3 u_lens_k;       // k1, k2, k3
uniform vec3 u_lens_scale;   // per channel

layout(location = 0) out vec4 o_color;

void main() {
  vec2 p = gl_FragCoord.xy - vec2(u_origin);
#ifndef DISTORTION
  o_color = method_resolve(u_reduced, p);
#else
  vec3 rgb;
  for (int c = 0; c < 3; ++c) {
    vec2 src = foveal_lens_source(p / u_screen_size, u_lens_center, u_lens_k, u_lens_scale[c], u_tan);
    bool inside = all(greaterThanEqual(src, vec2(0.0))) && all(lessThanEqual(src, vec2(1.0)));
    rgb[c] = inside ? method_resolve(u_reduced, src * u_screen_size)[c] : 0.0;
  }
  o_color = vec4(rgb, 1.0);
#endif
}
