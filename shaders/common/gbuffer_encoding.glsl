#ifndef GBUFFER_ENCODING_GLSL
#define GBUFFER_ENCODING_GLSL
// G-buffer normals: octahedral encoding into two signed-normalised channels.
vec2 encode_normal(vec3 n) {
  n /= abs(n.x) + abs(n.y) + abs(n.z);
  vec2 e = n.xy;
  if (n.z < 0.0) e = (1.0 - abs(n.yx)) * mix(vec2(-1.0), vec2(1.0), greaterThanEqual(n.xy, vec2(0.0)));
  return e;
}

vec3 decode_normal(vec2 e) {
  vec3 n = vec3(e, 1.0 - abs(e.x) - abs(e.y));
  float t = max(-n.z, 0.0);
  n.xy += mix(vec2(t), vec2(-t), greaterThanEqual(n.xy, vec2(0.0)));
  return normalize(n);
}
#endif
