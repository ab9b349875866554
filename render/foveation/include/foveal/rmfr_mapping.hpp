#pragma once
// RMFR's rectangular mapping on one axis, in normalised coordinates (docs/rmfr.md), and
// the per-eye quantities derived from σ. Header-only: foveal-rmfr, foveal's image-space
// tools and automatic f all use these. The GLSL twin is glsl/foveal/rmfr_mapping.glsl;
// tests hold the two together.
//
// Screen coordinate p and buffer coordinate u both lie in [0, 1]; c is the fovea, f > 0
// the axis parameter (a fraction of the axis length). D is the distance from the fovea
// to the edge on p's side (c on the low side, 1 - c on the high side). The paper's
// thin-lens mapping t = f|d| / (f + |d|), normalised so each edge lands on its edge,
// simplifies to
//     forward  u = c + d · (f + D) / (f + |d|),        d = p - c, |d| <= D
//     inverse  p = c + e · f / (f + D - |e|),          e = u - c, |e| <= D
// Neither divides by D, so a fovea on the border (D = 0 on one side) needs no clamping:
// that side simply holds no pixels. Both are continuous at the fovea; the sampling
// density (du/dp = (f + D)/f at the fovea, f/(f + D) at the edge) differs between the two
// sides when the fovea is off-centre.
//
// Thread safety: pure functions, callable from any thread.
#include <algorithm>
#include <cmath>

namespace foveal::rmfr {

inline double rmfr_side(double c, double d) { return d < 0 ? c : 1.0 - c; }

/// Screen -> buffer (both normalised).
inline double rmfr_forward(double p, double c, double f) {
  const double d = p - c;
  return c + d * (f + rmfr_side(c, d)) / (f + std::abs(d));
}

/// Buffer -> screen (both normalised).
inline double rmfr_inverse(double u, double c, double f) {
  const double e = u - c;
  const double D = rmfr_side(c, e);
  return c + e * f / (f + D - std::min(std::abs(e), D));
}

/// f standing for "no warp": both formulas reduce to u = p (f + x == f in float and double).
inline constexpr double kRmfrIdentityF = 1e30;

/// The f the mapping uses at level σ: σ = 1 renders at full rate, so it does not warp
/// (a warp at σ = 1 would oversample the fovea and undersample the periphery).
inline double rmfr_effective_f(double f, double sigma) { return sigma > 1.0 ? f : kRmfrIdentityF; }

/// A fovea coordinate fit for the mapping: NaN or infinite -> centre, else clamped to [0, 1].
inline double sanitize_fovea(double c) { return std::isfinite(c) ? std::clamp(c, 0.0, 1.0) : 0.5; }

/// Buffer size for a level σ: round(size / σ), at least 1.
inline int rmfr_buffer_size(int size, double sigma) {
  return std::max(1, static_cast<int>(std::lround(static_cast<double>(size) / std::max(sigma, 1.0))));
}

/// The screen pixel (0..size-1) whose sample fills buffer texel i of n: floor(inverse((i + 0.5)/n) · size).
inline int rmfr_source_pixel(int i, int n, int size, double c, double f) {
  const double p = rmfr_inverse((i + 0.5) / n, c, f);
  return std::clamp(static_cast<int>(std::floor(p * size)), 0, size - 1);
}

}  // namespace foveal::rmfr
