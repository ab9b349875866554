#include <algorithm>
#include <cmath>
#include <numbers>

#include "foveal/drivers/synthetic_source.hpp"

namespace foveal {

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kSaccadeLabelSpeed = 30.0;  // deg/s

// Minimum-jerk position profile: smooth start and stop, bell-shaped velocity.
double min_jerk(double tau) {
  tau = std::clamp(tau, 0.0, 1.0);
  return tau * tau * tau * (10.0 + tau * (-15.0 + 6.0 * tau));
}
}  // namespace

const char* gaze_event_name(GazeEvent e) {
  switch (e) {
    case GazeEvent::fixation: return "fixation";
    case GazeEvent::saccade: return "saccade";
    case GazeEvent::pursuit: return "pursuit";
    case GazeEvent::blink: return "blink";
  }
  return "?";
}

Status SyntheticOptions::validate() const {
  auto pos = [](double v) { return std::isfinite(v) && v > 0; };
  auto nonneg = [](double v) { return std::isfinite(v) && v >= 0; };
  if (!pos(rate_hz) || rate_hz > 10000) return bad_input("synthetic: rate_hz must be in (0, 10000]");
  if (!nonneg(duration_s)) return bad_input("synthetic: duration_s must be >= 0");
  if (!nonneg(noise_deg) || !nonneg(drift_deg_per_s)) return bad_input("synthetic: noise and drift must be >= 0");
  if (!pos(fixation_ms_min) || fixation_ms_max < fixation_ms_min) return bad_input("synthetic: fixation range invalid");
  if (!pos(saccade_deg_min) || saccade_deg_max < saccade_deg_min) return bad_input("synthetic: saccade range invalid");
  if (!pos(field_deg) || field_deg > 60) return bad_input("synthetic: field_deg must be in (0, 60]");
  if (!(pursuit_probability >= 0 && pursuit_probability <= 1)) return bad_input("synthetic: pursuit_probability must be in [0, 1]");
  if (!pos(pursuit_deg_per_s_min) || pursuit_deg_per_s_max < pursuit_deg_per_s_min) return bad_input("synthetic: pursuit range invalid");
  if (!nonneg(blink_rate_hz)) return bad_input("synthetic: blink_rate_hz must be >= 0");
  if (!pos(blink_ms_min) || blink_ms_max < blink_ms_min) return bad_input("synthetic: blink range invalid");
  if (!pos(depth_m_min) || depth_m_max < depth_m_min) return bad_input("synthetic: depth range invalid");
  if (!pos(ipd_mm) || ipd_mm > 200) return bad_input("synthetic: ipd_mm must be in (0, 200]");
  if (!nonneg(speed)) return bad_input("synthetic: speed must be >= 0");
  return {};
}

SyntheticGenerator::SyntheticGenerator(const SyntheticOptions& opts)
    : o_(opts), rng_state_(opts.seed * 0x9E3779B97F4A7C15ull + 0x632BE59BD9B4E019ull) {
  depth_m_ = o_.depth_m_min;
  begin_event();
}

double SyntheticGenerator::uniform() {
  // splitmix64: tiny, fast, identical everywhere.
  std::uint64_t z = (rng_state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

double SyntheticGenerator::gaussian() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  double u1 = uniform();
  while (u1 <= 0.0) u1 = uniform();
  const double u2 = uniform();
  const double r = std::sqrt(-2.0 * std::log(u1));
  spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
  has_spare_ = true;
  return r * std::cos(2.0 * std::numbers::pi * u2);
}

void SyntheticGenerator::begin_event() {
  const double now = static_cast<double>(index_) / o_.rate_hz;
  event_t0_ = now;
  from_az_ = az_;
  from_el_ = el_;
  ++event_index_;
  const bool first = index_ == 0 && event_index_ == 1;
  if (first || event_ != GazeEvent::fixation) {
    // After a saccade or pursuit (or at the start): fixate.
    event_ = GazeEvent::fixation;
    event_len_s_ = (o_.fixation_ms_min + uniform() * (o_.fixation_ms_max - o_.fixation_ms_min)) / 1000.0;
    drift_az_ = drift_el_ = 0;
    blink_end_s_ = -1;
    // A blink starts inside this fixation with probability rate * duration.
    if (uniform() < o_.blink_rate_hz * event_len_s_) {
      const double blink_len = (o_.blink_ms_min + uniform() * (o_.blink_ms_max - o_.blink_ms_min)) / 1000.0;
      const double start = now + uniform() * std::max(0.0, event_len_s_ - blink_len);
      blink_start_s_ = start;
      blink_end_s_ = start + blink_len;
      event_len_s_ = std::max(event_len_s_, blink_end_s_ - now);
    }
    return;
  }
  if (uniform() < o_.pursuit_probability) {
    event_ = GazeEvent::pursuit;
    const double speed = o_.pursuit_deg_per_s_min + uniform() * (o_.pursuit_deg_per_s_max - o_.pursuit_deg_per_s_min);
    const double dir = uniform() * 2.0 * std::numbers::pi;
    event_len_s_ = 0.3 + uniform() * 0.5;
    vel_az_ = speed * std::cos(dir);
    vel_el_ = speed * std::sin(dir);
    // Turn back when the path would leave the field.
    const double end_az = az_ + vel_az_ * event_len_s_, end_el = el_ + vel_el_ * event_len_s_;
    if (std::fabs(end_az) > o_.field_deg) vel_az_ = -vel_az_;
    if (std::fabs(end_el) > o_.field_deg) vel_el_ = -vel_el_;
    return;
  }
  event_ = GazeEvent::saccade;
  // Pick a landing point inside the field at an amplitude in range.
  double amp = 0, az = az_, el = el_;
  for (int tries = 0; tries < 32; ++tries) {
    amp = o_.saccade_deg_min + uniform() * (o_.saccade_deg_max - o_.saccade_deg_min);
    const double dir = uniform() * 2.0 * std::numbers::pi;
    az = az_ + amp * std::cos(dir);
    el = el_ + amp * std::sin(dir);
    if (std::fabs(az) <= o_.field_deg && std::fabs(el) <= o_.field_deg) break;
    az = std::clamp(az, -o_.field_deg, o_.field_deg);
    el = std::clamp(el, -o_.field_deg, o_.field_deg);
  }
  amp = std::hypot(az - az_, el - el_);
  to_az_ = az;
  to_el_ = el;
  event_len_s_ = (2.2 * amp + 21.0) / 1000.0;  // main sequence
  depth_m_ = o_.depth_m_min + uniform() * (o_.depth_m_max - o_.depth_m_min);
}

glm::vec3 SyntheticGenerator::eye_direction(int eye, double az_deg, double el_deg, double depth_m) const {
  // Target point in the head frame (mm), eyes at +-ipd/2 on x; -z forward.
  const double ca = std::cos(el_deg * kDeg);
  const double px = depth_m * 1000.0 * ca * std::sin(az_deg * kDeg);
  const double py = depth_m * 1000.0 * std::sin(el_deg * kDeg);
  const double pz = -depth_m * 1000.0 * ca * std::cos(az_deg * kDeg);
  const double ex = (eye == 0 ? -0.5 : 0.5) * o_.ipd_mm;
  const double dx = px - ex, dy = py, dz = pz;
  const double n = std::sqrt(dx * dx + dy * dy + dz * dz);
  return {static_cast<float>(dx / n), static_cast<float>(dy / n), static_cast<float>(dz / n)};
}

bool SyntheticGenerator::next(GazeSample& sample, GazeTruth& truth) {
  const double t = static_cast<double>(index_) / o_.rate_hz;
  if (o_.duration_s > 0 && t >= o_.duration_s) return false;
  while (t >= event_t0_ + event_len_s_) {
    if (event_ == GazeEvent::saccade) {
      az_ = to_az_;
      el_ = to_el_;
    }
    begin_event();
  }
  const double dt = 1.0 / o_.rate_hz;
  GazeEvent label = event_;
  switch (event_) {
    case GazeEvent::fixation: {
      // Fixational drift: a random walk of the given RMS speed.
      drift_az_ += gaussian() * o_.drift_deg_per_s * dt;
      drift_el_ += gaussian() * o_.drift_deg_per_s * dt;
      az_ = from_az_ + drift_az_;
      el_ = from_el_ + drift_el_;
      if (blink_end_s_ > 0 && t >= blink_start_s_ && t < blink_end_s_) label = GazeEvent::blink;
      break;
    }
    case GazeEvent::saccade: {
      const double tau = (t - event_t0_) / event_len_s_;
      const double s = min_jerk(tau);
      az_ = from_az_ + (to_az_ - from_az_) * s;
      el_ = from_el_ + (to_el_ - from_el_) * s;
      // Label by speed, as I-VT ground truth is: the slow first and last moments of the
      // movement (below 30 deg/s) still count as fixation.
      const double amp = std::hypot(to_az_ - from_az_, to_el_ - from_el_);
      const double speed = amp / event_len_s_ * 30.0 * tau * tau * (1.0 - tau) * (1.0 - tau);
      if (speed < kSaccadeLabelSpeed) label = GazeEvent::fixation;
      break;
    }
    case GazeEvent::pursuit:
      az_ = from_az_ + vel_az_ * (t - event_t0_);
      el_ = from_el_ + vel_el_ * (t - event_t0_);
      break;
    case GazeEvent::blink: break;
  }

  truth = {};
  truth.t_ns = static_cast<TimeNs>(std::llround(t * 1e9));
  truth.event = label;
  truth.azimuth_deg = az_;
  truth.elevation_deg = el_;
  truth.depth_m = depth_m_;
  truth.event_index = event_index_;

  sample = {};
  sample.t_ns = truth.t_ns;
  const double sd = o_.noise_deg / std::sqrt(2.0);  // per axis, so the 2-D RMS is noise_deg
  glm::vec3 sum{0.0f};
  for (int e = 0; e < 2; ++e) {
    truth.direction[e] = eye_direction(e, az_, el_, depth_m_);
    EyeSample& es = sample.eyes[e];
    es.origin_mm = {static_cast<float>((e == 0 ? -0.5 : 0.5) * o_.ipd_mm), 0.0f, 0.0f};
    es.pupil_mm = static_cast<float>(3.5 + 0.1 * gaussian());
    es.valid = kValidOrigin | kValidPupil | kValidOpenness;
    if (label == GazeEvent::blink) {
      es.openness = 0.0f;
      continue;
    }
    es.openness = 1.0f;
    // Measurement noise: perturb the true angles of this eye.
    const glm::vec3 d = truth.direction[e];
    const double az = std::atan2(d.x, -d.z) / kDeg + sd * gaussian();
    const double el = std::asin(std::clamp<double>(d.y, -1.0, 1.0)) / kDeg + sd * gaussian();
    const double ce = std::cos(el * kDeg);
    es.direction = {static_cast<float>(ce * std::sin(az * kDeg)), static_cast<float>(std::sin(el * kDeg)),
                    static_cast<float>(-ce * std::cos(az * kDeg))};
    es.valid |= kValidDirection;
    sum += es.direction;
  }
  if (label != GazeEvent::blink) {
    sample.combined.direction = sum / std::sqrt(sum.x * sum.x + sum.y * sum.y + sum.z * sum.z);
    sample.combined.valid = kValidDirection;
  }
  ++index_;
  return true;
}

}  // namespace foveal
