#include "foveal/quality/channel_quality.hpp"

#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>

namespace foveal {

namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

/// Means, population variances and covariance of the valid samples' angles, two-pass.
struct Moments {
  std::uint64_t n = 0;
  double mean_x = 0, mean_y = 0;
  double sxx = 0, syy = 0, sxy = 0;  ///< sums of squared deviations and of cross products
};

Moments moments(std::span<const AngleSample> samples) {
  Moments m;
  for (const AngleSample& s : samples)
    if (s.valid) {
      ++m.n;
      m.mean_x += s.gaze.azimuth_deg;
      m.mean_y += s.gaze.elevation_deg;
    }
  if (m.n == 0) return m;
  m.mean_x /= static_cast<double>(m.n);
  m.mean_y /= static_cast<double>(m.n);
  for (const AngleSample& s : samples)
    if (s.valid) {
      const double dx = s.gaze.azimuth_deg - m.mean_x, dy = s.gaze.elevation_deg - m.mean_y;
      m.sxx += dx * dx;
      m.syy += dy * dy;
      m.sxy += dx * dy;
    }
  return m;
}

}  // namespace

ChannelQuality measure_channel(std::span<const AngleSample> samples, double duration_s, double rate_hz) {
  ChannelQuality q;
  q.samples = samples.size();
  const Moments m = moments(samples);
  q.valid = m.n;
  const auto valid = static_cast<double>(q.valid);
  if (duration_s > 0 && rate_hz > 0) {
    q.expected_samples = duration_s * rate_hz;
    q.data_loss_pct = 100.0 * (1.0 - valid / q.expected_samples);
    q.effective_frequency_hz = valid / duration_s;
  }
  if (q.samples) q.invalid_pct = 100.0 * (1.0 - valid / static_cast<double>(q.samples));

  // RMS-S2S: only steps between consecutive recorded samples that are both valid.
  double sum_dx2 = 0, sum_dy2 = 0;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    if (!samples[i].valid || !samples[i - 1].valid) continue;
    const double dx = samples[i].gaze.azimuth_deg - samples[i - 1].gaze.azimuth_deg;
    const double dy = samples[i].gaze.elevation_deg - samples[i - 1].gaze.elevation_deg;
    sum_dx2 += dx * dx;
    sum_dy2 += dy * dy;
    ++q.s2s_pairs;
  }
  if (q.s2s_pairs) {
    const auto pairs = static_cast<double>(q.s2s_pairs);
    q.rms_s2s_deg = std::sqrt((sum_dx2 + sum_dy2) / pairs);
    q.rms_s2s_x_deg = std::sqrt(sum_dx2 / pairs);
    q.rms_s2s_y_deg = std::sqrt(sum_dy2 / pairs);
  }
  if (m.n >= 1) {
    q.std_x_deg = std::sqrt(m.sxx / valid);
    q.std_y_deg = std::sqrt(m.syy / valid);
    q.std_deg = std::hypot(q.std_x_deg, q.std_y_deg);
  }
  if (m.n >= 2) {
    // 2 k pi sx sy sqrt(1 - rho^2) with sample (n - 1) moments, written as the square root
    // of the covariance matrix's determinant: the same value, and defined when a
    // variance is zero (rho is not).
    const double k = -std::log(1.0 - kBceaProbability);
    const double vx = m.sxx / (valid - 1), vy = m.syy / (valid - 1), cxy = m.sxy / (valid - 1);
    q.bcea_deg2 = 2.0 * k * std::numbers::pi * std::sqrt(std::max(0.0, vx * vy - cxy * cxy));
  }
  return q;
}

std::optional<TargetOffset> mean_offset(std::span<const AngleSample> samples, const FickAngles& target) {
  // Forward along +z here (the tangent screen's convention): negate our -z forward.
  auto forward_z = [](const FickAngles& a) {
    const glm::dvec3 d = direction_from_fick(a);
    return glm::dvec3(d.x, d.y, -d.z);
  };
  const glm::dvec3 t = forward_z(target);
  TargetOffset out;
  for (const AngleSample& s : samples) {
    if (!s.valid) continue;
    const glm::dvec3 g = forward_z(s.gaze);
    // The angle between gaze and target (atan2 stays exact for small angles, acos does not),
    // in the direction of the gaze point from the target's on the plane at unit distance.
    const double angle = std::atan2(glm::length(glm::cross(g, t)), glm::dot(g, t));
    const double direction = std::atan2(g.y / g.z - t.y / t.z, g.x / g.z - t.x / t.z);
    out.x_deg += angle * std::cos(direction);
    out.y_deg += angle * std::sin(direction);
    ++out.samples;
  }
  if (out.samples == 0) return std::nullopt;
  out.x_deg *= kDegPerRad / static_cast<double>(out.samples);
  out.y_deg *= kDegPerRad / static_cast<double>(out.samples);
  out.offset_deg = std::hypot(out.x_deg, out.y_deg);
  return out;
}

}  // namespace foveal
