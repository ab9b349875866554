#pragma once
// The foveated, luminance-dependent spatio-temporal contrast sensitivity FovVideoVDP uses:
// the achromatic channel of Mantiuk et al.'s spatio-chromatic CSF (CIC 2020) with Rovamo's
// size model, scaled in frequency and size by cortical magnification (Dougherty et al.
// 2003) and in time by the Laird/Daly spatio-velocity CSF (docs/metrics.md, "JOD").
#include <array>
#include <memory>
#include <vector>

namespace foveal::perception {

/// Sensitivity (1 / threshold Weber contrast) for spatial frequency `rho` (cycles/deg),
/// temporal frequency `omega` (Hz), background luminance `lum` (cd/m²), eccentricity
/// `ecc` (deg); `sigma` < 0: the stimulus is -sigma cycles across; `k_cm` scales the
/// cortical magnification. Floored at 1e-4.
double csf_sensitivity(double rho, double omega, double lum, double ecc, double sigma, double k_cm);

/// The CSF tabulated for one temporal frequency on a 32³ grid (log2 frequency 1/16-64
/// cpd, log2 luminance 0.001-10⁴ cd/m², square root of eccentricity 0-120°) and read
/// trilinearly in log2 sensitivity: the form the reference evaluates it in.
class CsfTable {
 public:
  static constexpr int kN = 32;
  CsfTable(double omega, double sigma, double k_cm);
  /// log2 sensitivity at log2 frequency, log2 luminance, sqrt eccentricity (clamped).
  float log2_sensitivity(float log2_rho, float log2_lum, float sqrt_ecc) const;

 private:
  std::array<float, kN> rho_log_{}, lum_log_{}, ecc_sqrt_{};
  std::vector<float> s_log_;  ///< [lum][rho][ecc]
};

/// One table per (omega, sigma, k_cm) for the whole process (thread-safe): the metrics of
/// both eyes and of every display share it.
std::shared_ptr<const CsfTable> shared_csf_table(double omega, double sigma, double k_cm);

}  // namespace foveal::perception
