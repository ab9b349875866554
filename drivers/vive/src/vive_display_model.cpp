#include "foveal/drivers/vive/vive_display_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <glm/vec2.hpp>

namespace foveal::vive {

glm::dvec2 vive_source(const Config& cfg, int eye, int c, double u, double v) {
  const EyeOptics& o = cfg.eyes[static_cast<std::size_t>(eye)];
  const ChannelDistortion& d = o.rgb[static_cast<std::size_t>(c)];
  const double aspect = cfg.aspect_x_over_y;
  const double fx = 0.5 / (1.0 + o.grow_for_undistort), fy = fx * aspect;
  const double x = 2 * u - 1 - d.center_x, y = (2 * v - 1) / aspect - d.center_y;
  const double r2 = x * x + y * y;
  const double k = 1.0 / (1.0 + r2 * (d.coeffs[0] + r2 * (d.coeffs[1] + r2 * d.coeffs[2]))) + d.coeffs[3];
  return {0.5 + (x * k + d.center_x) * fx, 0.5 + (y * k + d.center_y) * fy};
}

EyeFrustum vive_frustum(const Config& cfg, int eye) {
  const EyeOptics& o = cfg.eyes[static_cast<std::size_t>(eye)];
  const double grow = 1.0 + o.grow_for_undistort;
  const double fx = o.fx / grow, fy = o.fy / grow, cx = o.cx / grow, cy = o.cy / grow;
  EyeFrustum f;
  f.tan_left = static_cast<float>(-(1 - cx) / fx);
  f.tan_right = static_cast<float>((1 + cx) / fx);
  f.tan_top = static_cast<float>((1 + cy) / fy);
  f.tan_bottom = static_cast<float>(-(1 - cy) / fy);
  return f;
}

namespace {

/// Our model's parameters: centre, k1..k3, per-channel scale, and the shift of our
/// frustum against Monado's (normalised): our model maps its centre to itself, the
/// configuration's does not (its centre is scaled about the image middle by the grow).
constexpr std::size_t kParams = 10;
using Params = std::array<double, kParams>;

/// Where our model samples, in Monado's rendered-image coordinates.
glm::dvec2 ours(const Params& p, int c, glm::dvec2 q, glm::dvec2 span) {
  const glm::dvec2 centre(p[0], p[1]);
  const glm::dvec2 x = (q - centre) * span;
  const double r2 = x.x * x.x + x.y * x.y;
  return centre + (q - centre) * (p[5 + c] * (1 + r2 * (p[2] + r2 * (p[3] + r2 * p[4])))) + glm::dvec2(p[8], p[9]);
}

struct Sample {
  glm::dvec2 panel;
  std::array<glm::dvec2, 3> target;
};

/// Residuals in rendered-image pixels, x and y of every sample and channel.
void residuals(const Params& p, const std::vector<Sample>& s, glm::dvec2 span, glm::dvec2 px, std::vector<double>& out) {
  out.clear();
  for (const Sample& q : s)
    for (int c = 0; c < 3; ++c) {
      const glm::dvec2 d = (ours(p, c, q.panel, span) - q.target[static_cast<std::size_t>(c)]) * px;
      out.push_back(d.x);
      out.push_back(d.y);
    }
}

/// Solves the kParams-square system a x = b (Gaussian elimination, partial pivoting); false if singular.
bool solve(std::array<std::array<double, kParams>, kParams> a, std::array<double, kParams> b, std::array<double, kParams>& x) {
  for (std::size_t i = 0; i < kParams; ++i) {
    std::size_t best = i;
    for (std::size_t r = i + 1; r < kParams; ++r)
      if (std::fabs(a[r][i]) > std::fabs(a[best][i])) best = r;
    if (std::fabs(a[best][i]) < 1e-300) return false;
    std::swap(a[i], a[best]);
    std::swap(b[i], b[best]);
    for (std::size_t r = i + 1; r < kParams; ++r) {
      const double f = a[r][i] / a[i][i];
      for (std::size_t c = i; c < kParams; ++c) a[r][c] -= f * a[i][c];
      b[r] -= f * b[i];
    }
  }
  for (std::size_t i = kParams; i-- > 0;) {
    double s = b[i];
    for (std::size_t c = i + 1; c < kParams; ++c) s -= a[i][c] * x[c];
    x[i] = s / a[i][i];
  }
  return true;
}

double sum_squares(const std::vector<double>& r) {
  double s = 0;
  for (double v : r) s += v * v;
  return s;
}

/// Levenberg-Marquardt with a forward-difference Jacobian.
Params fit(Params p, const std::vector<Sample>& s, glm::dvec2 span, glm::dvec2 px) {
  std::vector<double> r, r2;
  residuals(p, s, span, px, r);
  double cost = sum_squares(r);
  double lambda = 1e-3;
  std::vector<std::array<double, kParams>> jac(r.size());
  for (int iter = 0; iter < 60; ++iter) {
    for (std::size_t k = 0; k < kParams; ++k) {
      Params q = p;
      const double h = 1e-7 * std::max(1.0, std::fabs(p[k]));
      q[k] += h;
      residuals(q, s, span, px, r2);
      for (std::size_t i = 0; i < r.size(); ++i) jac[i][k] = (r2[i] - r[i]) / h;
    }
    std::array<std::array<double, kParams>, kParams> jtj{};
    std::array<double, kParams> jtr{};
    for (std::size_t i = 0; i < r.size(); ++i)
      for (std::size_t a = 0; a < kParams; ++a) {
        jtr[a] -= jac[i][a] * r[i];
        for (std::size_t b = 0; b < kParams; ++b) jtj[a][b] += jac[i][a] * jac[i][b];
      }
    bool improved = false;
    for (int tries = 0; tries < 10 && !improved; ++tries) {
      auto m = jtj;
      for (std::size_t a = 0; a < kParams; ++a) m[a][a] *= 1 + lambda;
      std::array<double, kParams> step{};
      if (!solve(m, jtr, step)) {
        lambda *= 10;
        continue;
      }
      Params q = p;
      for (std::size_t a = 0; a < kParams; ++a) q[a] += step[a];
      residuals(q, s, span, px, r2);
      const double c2 = sum_squares(r2);
      if (c2 < cost) {
        const bool converged = cost - c2 < 1e-12 * cost;
        p = q, r = r2, cost = c2, lambda = std::max(1e-9, lambda / 10), improved = true;
        if (converged) return p;
      } else {
        lambda *= 10;
      }
    }
    if (!improved) break;
  }
  return p;
}

}  // namespace

Result<DisplayModel> vive_display_model(const Config& cfg, DistortionFit* fit_out) {
  DisplayModel m;
  std::string name = "vive_" + cfg.model_number;
  for (char& ch : name) ch = std::isalnum(static_cast<unsigned char>(ch)) ? static_cast<char>(std::tolower(ch)) : '_';
  m.name = name;
  m.eye_width = cfg.eye_width;
  m.eye_height = cfg.eye_height;
  m.ipd_mm = static_cast<float>(cfg.ipd_m * 1000.0);
  m.refresh_hz = 90.0;  // assumed: the configuration does not say
  m.edid_vendor = "HVR";
  DistortionFit report;
  constexpr int kGrid = 25;
  for (int e = 0; e < 2; ++e) {
    const EyeFrustum f = vive_frustum(cfg, e);
    const glm::dvec2 span(double(f.tan_right) - f.tan_left, double(f.tan_top) - f.tan_bottom);
    const glm::dvec2 px(cfg.eye_width, cfg.eye_height);
    const EyeOptics& o = cfg.eyes[static_cast<std::size_t>(e)];
    // The panel points the configuration's polynomial is meant for (r² within its cutoff).
    std::vector<Sample> samples;
    for (int i = 0; i <= kGrid; ++i)
      for (int j = 0; j <= kGrid; ++j) {
        const double u = double(i) / kGrid, v = double(j) / kGrid;
        const ChannelDistortion& g = o.rgb[1];
        const double x = 2 * u - 1 - g.center_x, y = (2 * v - 1) / cfg.aspect_x_over_y - g.center_y;
        if (x * x + y * y > o.undistort_r2_cutoff) continue;
        Sample s{{u, v}, {}};
        for (int c = 0; c < 3; ++c) s.target[static_cast<std::size_t>(c)] = vive_source(cfg, e, c, u, v);
        samples.push_back(s);
      }
    if (samples.size() < 20) return bad_input("vive config: eye " + std::to_string(e) + ": undistort_r2_cutoff leaves too few panel points to fit");
    // Start: the green lens centre on the panel, the grow as the scale, no distortion.
    const ChannelDistortion& g = o.rgb[1];
    Params p{(1 + g.center_x) / 2, (1 + cfg.aspect_x_over_y * g.center_y) / 2, 0, 0, 0, 0, 0, 0, 0, 0};
    for (int c = 0; c < 3; ++c) p[5 + static_cast<std::size_t>(c)] = 1.0 / (1.0 + o.grow_for_undistort);
    p = fit(p, samples, span, px);
    std::vector<double> r;
    residuals(p, samples, span, px, r);
    double sum2 = 0, worst = 0;
    for (std::size_t i = 0; i + 1 < r.size(); i += 2) {
      const double d2 = r[i] * r[i] + r[i + 1] * r[i + 1];
      sum2 += d2;
      worst = std::max(worst, std::sqrt(d2));
    }
    report.rms_px[static_cast<std::size_t>(e)] = std::sqrt(sum2 / double(r.size() / 2));
    report.max_px[static_cast<std::size_t>(e)] = worst;
    report.points = samples.size();
    // Our frustum: Monado's shifted so that our model's coordinates are its own (x right,
    // y down in normalised units; tangents x right, y up).
    EyeFrustum& ff = m.frustum[static_cast<std::size_t>(e)];
    ff = f;
    ff.tan_left += static_cast<float>(p[8] * span.x), ff.tan_right += static_cast<float>(p[8] * span.x);
    ff.tan_top -= static_cast<float>(p[9] * span.y), ff.tan_bottom -= static_cast<float>(p[9] * span.y);
    LensDistortion& d = m.distortion[static_cast<std::size_t>(e)];
    d.enabled = true;
    d.center = {static_cast<float>(p[0]), static_cast<float>(p[1])};
    d.k1 = static_cast<float>(p[2]), d.k2 = static_cast<float>(p[3]), d.k3 = static_cast<float>(p[4]);
    d.channel_scale = {static_cast<float>(p[5]), static_cast<float>(p[6]), static_cast<float>(p[7])};
  }
  if (Status s = m.validate("vive config (converted)"); !s) return s.error();
  if (fit_out) *fit_out = report;
  return m;
}

std::string vive_model_source(const Config& cfg, const DistortionFit& fit) {
  char b[320];
  std::snprintf(b, sizeof b,
                "read from the headset's configuration (%s%s%s); DISTORT_DPOLY3 distortion fitted over %zu panel points "
                "per eye: rms %.2f/%.2f px, max %.2f/%.2f px (left/right); refresh_hz and edid_vendor assumed",
                cfg.model_number.c_str(), cfg.serial.empty() ? "" : ", serial ", cfg.serial.c_str(), fit.points,
                fit.rms_px[0], fit.rms_px[1], fit.max_px[0], fit.max_px[1]);
  return b;
}

}  // namespace foveal::vive
