// FovVideoVDP's CSF (docs/metrics.md, "JOD"): formulas and fitted values from
// R. K. Mantiuk, M. Kim, M. Ashraf, Q. Xu, M. R. Luo, J. Martinovic, S. Wuerger,
// "Practical color contrast sensitivity functions for luminance levels up to 10000 cd/m²",
// Color and Imaging Conference 2020 (the cone-contrast model, fit of 16/09/2020);
// J. Rovamo et al., Vision Research 33(18), 1993 (size); R. F. Dougherty et al., Journal of
// Vision 3(10), 2003 (cortical magnification M = 29.2 / (e + 3.67)); J. Laird, M. Rosen,
// J. Pelz, E. Montag, S. Daly, SPIE 6057, 2006 (spatio-velocity CSF).
#include "foveal/perception/csf.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <tuple>

namespace foveal::perception {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Luminance dependence of a CSF parameter: 1, 3 or 5 fitted values.
double lum_dep(const double* p, int n, double lum) {
  if (n == 1) return p[0];
  const double a = p[0] * std::pow(1.0 + p[1] / lum, -p[2]);
  if (n == 3) return a;
  return a * (1.0 - std::pow(1.0 + p[3] / lum, -p[4]));
}

struct Mechanism {
  double s_max[5];
  int n_s_max;
  double f_max[3];
  int n_f_max;
  double bw, gamma, ac_prime;
};

// Achromatic, red-green, yellow-violet mechanisms (CIC 2020, cone-contrast model).
constexpr Mechanism kMech[3] = {
    {{356404, 6.2726, 0.320031, 895943, 7.77919e-05}, 5, {2.3021, 3317.45, 0.186215}, 3, 1.07516, 1.1107, 52.9768},
    {{423.978, 15.4032, 0.50343, 0, 0}, 3, {0.122699, 0, 0}, 1, 2.70669, 1.72903, 1.38437},
    {{11811.9, 196.342, 0.339396, 0, 0}, 3, {7.1099e-08, 0, 0}, 1, 5.3416, 1.47263, 0.282573},
};

// Cone contrast (L, M, S) to the three mechanisms' contrasts (signs included).
constexpr double kLmsToMech[3][3] = {
    {1.0, 0.256197, 6.42477e-07},
    {1.0, -0.933541, 0.00373304},
    {-0.00130319, -1.1504, 1.0},
};

// Log-parabola in frequency times Rovamo's area term; chromatic mechanisms are low-pass.
double mechanism_sensitivity(int c, double rho, double area, double lum) {
  const Mechanism& m = kMech[c];
  const double s_max = lum_dep(m.s_max, m.n_s_max, lum);
  const double f_max = lum_dep(m.f_max, m.n_f_max, lum);
  const double d = std::log10(rho) - std::log10(f_max);
  double s_peak = s_max / std::pow(10.0, d * d / (0.5 * std::pow(2.0, m.bw)));
  if (c > 0 && rho < f_max) s_peak = s_max;
  const double f0 = 0.65;
  const double k = m.ac_prime + area * f0;
  const double ag = std::pow(area, m.gamma) * rho * rho;
  return s_peak * std::sqrt(ag / (k + ag));
}

// Achromatic sensitivity at a D65 background of `lum` cd/m² (CIE 2006 LMS).
double achromatic_sensitivity(double rho, double area, double lum) {
  // D65 (0.9504, 1, 1.0888) through the XYZ -> CIE 2006 LMS matrix for an LED LCD.
  const double lms_white[3] = {
      0.187596268556126 * 0.9504 + 0.585168649077728 - 0.026384263306304 * 1.0888,
      -0.133397430663221 * 0.9504 + 0.405505777260049 + 0.034502127690364 * 1.0888,
      0.000244379021663 * 0.9504 - 0.000542995890619 + 0.019406849066323 * 1.0888,
  };
  const double delta[3] = {0.698, 0.302, 0.019613};  // the luminance direction in LMS
  double cc[3], cc_norm2 = 0;
  for (int i = 0; i < 3; ++i) {
    cc[i] = delta[i] / (lum * lms_white[i]);
    cc_norm2 += cc[i] * cc[i];
  }
  const double mech_lum = lum * (lms_white[0] + lms_white[1]);
  double c2 = 0;
  for (int m = 0; m < 3; ++m) {
    const double cm = std::abs(kLmsToMech[m][0] * cc[0] + kLmsToMech[m][1] * cc[1] + kLmsToMech[m][2] * cc[2]);
    const double cn = cm * mechanism_sensitivity(m, rho, area, mech_lum);
    c2 += cn * cn;
  }
  // Threshold along the direction: cone contrast |cc| / C, as an RMS over the 3 cones.
  return std::sqrt(c2) * std::sqrt(3.0) / std::sqrt(cc_norm2);
}

// Laird et al.'s spatio-velocity CSF, velocity floored at 0.1 deg/s (fixational drift).
double spatio_velocity(double rho, double vel) {
  const double v = std::max(vel, 0.1);
  const double c0 = 0.6329, c1 = 0.8404, c2 = 0.7986, s1 = 6.1, s2 = 7.3, p1 = 45.9;
  const double l = std::abs(std::log10(c2 * v / 3.0));
  const double k = s1 + s2 * l * l * l;
  const double rho_max = p1 / (c2 * v + 2.0);
  const double w = c1 * 2.0 * kPi * rho;
  return k * c0 * c1 * c2 * v * w * w * std::exp(-(c1 * 4.0 * kPi * rho) / rho_max);
}

}  // namespace

double csf_sensitivity(double rho, double omega, double lum, double ecc, double sigma, double k_cm) {
  const double size = sigma < 0 ? -sigma / rho : sigma;
  // Relative cortical magnification: frequencies scale up and sizes down with eccentricity.
  const double m_rel = std::pow(3.67 / (ecc + 3.67), k_cm);
  const double area = kPi * (size * m_rel) * (size * m_rel);
  const double rho_cm = rho / m_rel;
  const double temporal = spatio_velocity(rho_cm, omega / rho_cm) / (spatio_velocity(rho_cm, 0.0) + 1e-5);
  return std::max(achromatic_sensitivity(rho_cm, area, lum) * temporal, 1e-4);
}

namespace {
constexpr double kRhoMin = 1.0 / 16.0, kRhoMax = 64.0, kLumMin = 0.001, kLumMax = 10000.0, kEccMax = 120.0;
}

CsfTable::CsfTable(double omega, double sigma, double k_cm) : s_log_(static_cast<std::size_t>(kN * kN * kN)) {
  for (int i = 0; i < kN; ++i) {
    const double t = static_cast<double>(i) / (kN - 1);
    rho_log_[static_cast<std::size_t>(i)] = static_cast<float>(std::log2(kRhoMin) + t * (std::log2(kRhoMax) - std::log2(kRhoMin)));
    lum_log_[static_cast<std::size_t>(i)] = static_cast<float>(std::log2(kLumMin) + t * (std::log2(kLumMax) - std::log2(kLumMin)));
    ecc_sqrt_[static_cast<std::size_t>(i)] = static_cast<float>(t * std::sqrt(kEccMax));
  }
  std::size_t k = 0;
  for (int l = 0; l < kN; ++l)
    for (int r = 0; r < kN; ++r)
      for (int e = 0; e < kN; ++e) {
        const double ecc = static_cast<double>(ecc_sqrt_[static_cast<std::size_t>(e)]) * ecc_sqrt_[static_cast<std::size_t>(e)];
        s_log_[k++] = static_cast<float>(std::log2(csf_sensitivity(std::exp2(rho_log_[static_cast<std::size_t>(r)]), omega,
                                                                   std::exp2(lum_log_[static_cast<std::size_t>(l)]), ecc, sigma, k_cm)));
      }
}

namespace {
// Cell index and fraction on a uniform axis, clamped to its ends.
inline void locate(float q, float q0, float q1, int& i, float& f) {
  const float u = std::clamp((q - q0) / (q1 - q0), 0.0f, 1.0f) * static_cast<float>(CsfTable::kN - 1);
  i = std::min(static_cast<int>(u), CsfTable::kN - 2);
  f = u - static_cast<float>(i);
}
}  // namespace

float CsfTable::log2_sensitivity(float log2_rho, float log2_lum, float sqrt_ecc) const {
  int ir, il, ie;
  float fr, fl, fe;
  locate(log2_rho, rho_log_.front(), rho_log_.back(), ir, fr);
  locate(log2_lum, lum_log_.front(), lum_log_.back(), il, fl);
  locate(sqrt_ecc, ecc_sqrt_.front(), ecc_sqrt_.back(), ie, fe);
  const auto at = [&](int l, int r, int e) {
    return s_log_[(static_cast<std::size_t>(l) * kN + static_cast<std::size_t>(r)) * kN + static_cast<std::size_t>(e)];
  };
  float v[2][2];
  for (int dl = 0; dl < 2; ++dl)
    for (int dr = 0; dr < 2; ++dr)
      v[dl][dr] = at(il + dl, ir + dr, ie) * (1 - fe) + at(il + dl, ir + dr, ie + 1) * fe;
  const float a = v[0][0] * (1 - fr) + v[0][1] * fr;
  const float b = v[1][0] * (1 - fr) + v[1][1] * fr;
  return a * (1 - fl) + b * fl;
}

std::shared_ptr<const CsfTable> shared_csf_table(double omega, double sigma, double k_cm) {
  static std::mutex mu;
  static std::map<std::tuple<double, double, double>, std::shared_ptr<const CsfTable>> tables;
  const std::lock_guard<std::mutex> lock(mu);
  auto& t = tables[{omega, sigma, k_cm}];
  if (!t) t = std::make_shared<const CsfTable>(omega, sigma, k_cm);
  return t;
}

}  // namespace foveal::perception
