// Anisotropic texture filtering over an explicit footprint, done in the shader: the
// visibility pipeline's material pass knows each texel's footprint (the mapping's
// Jacobian times the screen-space UV derivatives) but runs as a full-screen pass, whose
// implicit derivatives mean nothing, and llvmpipe ignores explicit gradients (textureGrad)
// and explicit levels (textureLod) on anisotropic samplers (docs/rmfr.md, "Texture
// filtering"). So the textures are read through isotropic trilinear samplers
// (Scene::isotropic_samplers) and the anisotropy is built from taps, the way the
// EXT_texture_filter_anisotropic specification describes hardware doing it.
const int MAX_ANISOTROPY = 8;  // the scene textures' GL_TEXTURE_MAX_ANISOTROPY (gpu_upload.cpp)

// The screen footprint a texel's texture reads are filtered over, from its mapping
// footprint (screen-pixel steps of one texel step, columns x and y): each axis at 0.35 of
// its length, and never under one pixel. The resolve already blurs each texel over a
// bilinear tent of its own width, so the reads need remove only what that leaves to
// alias; filtering over the whole footprint blurred twice over (Dungeon, RMFR σ 2: -1 dB
// FPSNR against the G-buffer pipeline; 0.35 measured best of 0, 0.35, 0.5 and 1:
// docs/results/pipeline_quality.md). Never under a pixel: RMFR magnifies the fovea, and a
// texel there must not be sharper than the full-resolution frame it stands in for. At
// σ = 1 it is the pixel's own footprint, as in the G-buffer pass.
mat2 filter_footprint(mat2 texel) {
  for (int c = 0; c < 2; ++c) {
    float len = length(texel[c]);
    if (len > 0.0) texel[c] *= max(0.35, 1.0 / len);
  }
  return texel;
}

// A read of `tex` filtered over the ellipse that texture-coordinate steps dx and dy
// (its conjugate semi-axes) span, like an EWA filter (Heckbert; llvmpipe's anisotropic
// sampling is one, and the G-buffer pass's reads are compared against it): the ellipse's
// axes from the singular values of [dx dy] in texels; up to MAX_ANISOTROPY trilinear taps
// spread over the major axis's diameter, Gaussian-weighted (exp(-2 r²), r = 1 at the
// rim), each at the level of detail of the minor axis (raised where the anisotropy
// exceeds the cap, as hardware does). Never finer than the minor axis: the specification's
// log2(major / taps), with taps rounded up, falls up to a level below it for a nearly round
// footprint, whose two taps then read too fine a level to cover its width, and that aliasing
// crawls as the view moves. Full rate through this pipeline against the G-buffer
// pipeline's, Dungeon at 1440×800: 41.9 dB FPSNR with the specification's level, 43.9 dB
// with the minor axis's (the closest of 0.8 to 1.7 times it).
vec4 texture_anisotropic(sampler2D tex, vec2 uv, vec2 dx, vec2 dy) {
  vec2 size = vec2(textureSize(tex, 0));
  vec2 a = dx * size, b = dy * size;
  // M = J Jᵀ; its eigenvalues are the squared axis lengths of the footprint ellipse.
  float m00 = a.x * a.x + b.x * b.x, m01 = a.x * a.y + b.x * b.y, m11 = a.y * a.y + b.y * b.y;
  float half_trace = 0.5 * (m00 + m11);
  float root = sqrt(max(half_trace * half_trace - (m00 * m11 - m01 * m01), 0.0));
  float major = sqrt(half_trace + root), minor = sqrt(max(half_trace - root, 0.0));
  if (!(major > 0.0) || isinf(major)) return textureLod(tex, uv, 0.0);  // degenerate or NaN footprint
  int taps = int(clamp(ceil(major / max(minor, 1e-6)), 1.0, float(MAX_ANISOTROPY)));
  float lod = clamp(log2(max(major / float(taps), minor)), -16.0, 16.0);
  if (taps == 1) return textureLod(tex, uv, lod);
  // The major axis: the eigenvector of M for its larger eigenvalue, in texture coordinates.
  vec2 axis = abs(m01) > 1e-12 * (m00 + m11) ? vec2(m01, half_trace + root - m00) : (m00 >= m11 ? vec2(1.0, 0.0) : vec2(0.0, 1.0));
  vec2 radius = normalize(axis) * major / size;
  vec4 sum = vec4(0.0);
  float weights = 0.0;
  for (int i = 0; i < taps; ++i) {
    float r = (2.0 * float(i) + 1.0) / float(taps) - 1.0;  // tap centres across [-1, 1]
    float w = exp(-2.0 * r * r);
    sum += w * textureLod(tex, uv + r * radius, lod);
    weights += w;
  }
  return sum / weights;
}
