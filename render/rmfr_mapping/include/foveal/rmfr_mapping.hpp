#pragma once
// RMFR's rectangular mapping on one axis, in normalised coordinates (docs/rmfr.md), and
// the per-eye quantities derived from σ. Header-only, on the ground floor: foveal-rmfr,
// foveal's image-space tools and automatic f all use these. The GLSL twin is
// render/foveation/glsl/foveal/rmfr_mapping.glsl (embedded in and installed with
// foveal-rmfr); tests hold the two together.
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

/// The periphery's sampling floor, in reduced-buffer texels per screen pixel along an axis
/// (docs/stability.md, "RMFR's periphery floor"). The far edge is sampled at f / ((f + D)·σ):
/// as f -> 0 a handful of texels cover the far side, each showing whatever one sample hit.
/// 1/48 lies just below the coarsest of the operating range (σ 4, f 0.1, the fovea on a
/// border: 1/44), so nothing there changes.
inline constexpr double kRmfrPeripheryFloor = 1.0 / 48;

/// The smallest f that keeps the far edge of an axis (fovea c, D = max(c, 1 - c)) at
/// min(kRmfrPeripheryFloor, 1/σ²) texels per pixel: f / (f + D) >= r for r = σ times that.
/// The density at the fovea's far side times the one at its edge is 1/σ² for every f, so
/// the 1/σ² cap (it binds above σ = √48 ≈ 6.9) never lowers the fovea below one texel per
/// pixel: the floor only takes away samples that repeat the same pixel. It is at most
/// 0.169 (σ = √48, c on a border), so f >= 0.17 is never raised. 0 at σ <= 1.
inline double rmfr_f_floor(double sigma, double c) {
  if (!(sigma > 1.0)) return 0.0;
  const double D = std::max(c, 1.0 - c);
  const double r = std::min(sigma * kRmfrPeripheryFloor, 1.0 / sigma);
  return D * r / (1.0 - r);
}

/// The f the mapping uses at level σ with the fovea at c on that axis (sanitised, either
/// frame): σ = 1 renders at full rate, so it does not warp (a warp at σ = 1 would
/// oversample the fovea and undersample the periphery); above it, f no smaller than
/// rmfr_f_floor.
inline double rmfr_effective_f(double f, double sigma, double c) {
  return sigma > 1.0 ? std::max(f, rmfr_f_floor(sigma, c)) : kRmfrIdentityF;
}

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
