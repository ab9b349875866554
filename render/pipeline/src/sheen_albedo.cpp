#include "sheen_albedo.hpp"

#include <algorithm>
#include <cmath>

namespace foveal::render::detail {

namespace {
constexpr double kPi = 3.14159265358979323846;

// The lobe as lighting.glsl has it: α kept above 1e-3.
double d_charlie(double n_dot_h, double roughness) {
  const double alpha = std::max(roughness * roughness, 1e-3), inv = 1.0 / alpha;
  const double sin2 = std::max(1.0 - n_dot_h * n_dot_h, 0.0);
  return (2.0 + inv) * std::pow(sin2, 0.5 * inv) / (2.0 * kPi);
}

double v_neubelt(double n_dot_v, double n_dot_l) { return 1.0 / (4.0 * (n_dot_l + n_dot_v - n_dot_l * n_dot_v)); }
}  // namespace

double sheen_albedo(double mu, double roughness) {
  // Midpoint rule over (θ_l, φ_l); v in the xz plane, n = z. The lobe is smooth and wide
  // (it peaks at grazing half vectors), so 96 × 96 points hold it to ~1e-3.
  constexpr int kTheta = 96, kPhi = 96;
  mu = std::clamp(mu, 1e-4, 1.0);
  const double vx = std::sqrt(1.0 - mu * mu), vz = mu;
  double sum = 0.0;
  for (int a = 0; a < kTheta; ++a) {
    const double theta = (a + 0.5) * (0.5 * kPi / kTheta);
    const double lz = std::cos(theta), st = std::sin(theta);
    for (int b = 0; b < kPhi; ++b) {
      const double phi = (b + 0.5) * (2.0 * kPi / kPhi);
      const double lx = st * std::cos(phi), ly = st * std::sin(phi);
      double hx = lx + vx, hy = ly, hz = lz + vz;
      const double len = std::sqrt(hx * hx + hy * hy + hz * hz);
      if (len <= 0.0) continue;
      const double n_dot_h = hz / len;
      sum += d_charlie(n_dot_h, roughness) * v_neubelt(mu, lz) * lz * st;
    }
  }
  return std::clamp(sum * (0.5 * kPi / kTheta) * (2.0 * kPi / kPhi), 0.0, 1.0);
}

std::vector<float> sheen_albedo_table(int size) {
  std::vector<float> t(static_cast<std::size_t>(size) * static_cast<std::size_t>(size));
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i)
      t[static_cast<std::size_t>(j) * static_cast<std::size_t>(size) + static_cast<std::size_t>(i)] =
          static_cast<float>(sheen_albedo((i + 0.5) / size, (j + 0.5) / size));
  return t;
}

}  // namespace foveal::render::detail
