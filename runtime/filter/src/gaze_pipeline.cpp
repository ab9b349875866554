#include "foveal/runtime/gaze_pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace foveal {

namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
// Low-pass cutoff of the velocity predict_fovea extrapolates (docs/filtering.md,
// "Prediction"): lower is steadier in fixation, higher follows a pursuit's changes
// sooner. 4 Hz is the best of 1, 2, 4 and 8 on synthetic 0.5 deg noise and within
// 0.02 deg of 8 Hz on the Vive recordings (docs/results/latency/prediction.md).
constexpr double kVelocityCutoffHz = 4.0;
constexpr double kMaxLagS = 0.1;  // a lag estimate beyond this (slow settling) is not trusted

// Angle between two unit vectors from their chord: exact to 1e-4 deg below 10 deg,
// and only compared against thresholds of a degree or so: no trigonometry needed.
double chord_deg(glm::vec3 a, glm::vec3 b) {
  const glm::vec3 d = a - b;
  return std::sqrt(static_cast<double>(d.x) * d.x + static_cast<double>(d.y) * d.y + static_cast<double>(d.z) * d.z) *
         kDegPerRad;
}

glm::vec3 unit_from_tangent(double u, double v) {
  const double n = 1.0 / std::sqrt(u * u + v * v + 1.0);
  return {static_cast<float>(u * n), static_cast<float>(v * n), static_cast<float>(-n)};
}

}  // namespace

GazePipeline::GazePipeline(DisplayModel model, FilterConfig config) : model_(std::move(model)), cfg_(config) {
  for (Eye e : kEyes) {
    const auto i = static_cast<std::size_t>(e);
    const EyeFrustum& f = model_.eye(e);
    const double m = cfg_.fov_margin_deg / kDegPerRad;
    auto widen = [m](double tan_edge, double sign) {
      const double a = std::atan(tan_edge) + sign * m;
      return std::abs(a) >= std::numbers::pi / 2 - 1e-3 ? sign * 1e3 : std::tan(a);
    };
    valid_box_[i] = {static_cast<float>(widen(f.tan_left, -1)), static_cast<float>(widen(f.tan_right, 1)),
                     static_cast<float>(widen(f.tan_bottom, -1)), static_cast<float>(widen(f.tan_top, 1))};
    const glm::vec3 c = model_.pixel_to_direction(
        e, {0.5f * static_cast<float>(model_.eye_width), 0.5f * static_cast<float>(model_.eye_height)});
    centre_u_[i] = c.x / -c.z;
    centre_v_[i] = c.y / -c.z;
  }
  reset();
}

void GazePipeline::reset() {
  // The 1€ works in tangent units; its beta is given per deg/s: one tangent unit per
  // second is about 57 deg/s near the centre.
  OneEuroParams p = cfg_.one_euro;
  p.beta *= kDegPerRad;
  for (std::size_t i = 0; i < 2; ++i) {
    eyes_[i] = EyeTrack{};
    eyes_[i].u = OneEuroFilter(p);
    eyes_[i].v = OneEuroFilter(p);
    eyes_[i].out_u = centre_u_[i];
    eyes_[i].out_v = centre_v_[i];
  }
  have_vergence_ = false;
}

bool GazePipeline::validate(const EyeSample& e, Eye eye, glm::vec3& unit) const {
  if (!e.has(kValidDirection)) return false;
  const glm::vec3 d = e.direction;
  if (!std::isfinite(d.x) || !std::isfinite(d.y) || !std::isfinite(d.z)) return false;
  const double len2 = static_cast<double>(d.x) * d.x + static_cast<double>(d.y) * d.y + static_cast<double>(d.z) * d.z;
  const double tol = cfg_.unit_tolerance;
  if (!(len2 >= (1 - tol) * (1 - tol) && len2 <= (1 + tol) * (1 + tol)) || !(d.z < 0.0f)) return false;
  if (e.has(kValidOpenness) && e.openness < cfg_.min_openness) return false;
  const float u = d.x / -d.z, v = d.y / -d.z;
  const EyeFrustum& b = valid_box_[static_cast<std::size_t>(eye)];
  if (!(u >= b.tan_left && u <= b.tan_right && v >= b.tan_bottom && v <= b.tan_top)) return false;
  unit = d / static_cast<float>(std::sqrt(len2));
  return true;
}

void GazePipeline::snap(EyeTrack& t, double u, double v, TimeNs t_ns) {
  // Jump to the new point, then settle (running mean until the 1€ takes over).
  t.u.reset(u, static_cast<double>(t_ns) * 1e-9, true);
  t.v.reset(v, static_cast<double>(t_ns) * 1e-9, true);
  t.out_u = u;
  t.out_v = v;
  t.vel_u = t.vel_v = 0;
  t.vel_from_u = u;
  t.vel_from_v = v;
  t.vel_from_t = t_ns;
  t.vel_known = true;
}

void GazePipeline::track_velocity(EyeTrack& t, TimeNs t_ns) const {
  // The derivative of the smoothed gaze, not the 1€'s own derivative: that one is taken
  // against the last *filtered* value, so in steady pursuit it reads the speed divided
  // by the filter's weight a (1/a times too fast: predict_ms's overshoot). The smoothed
  // gaze moves at the true speed once the filter has caught up; the low-pass keeps its
  // noise small enough to extrapolate.
  const double u = t.u.value(), v = t.v.value();
  const double dt = static_cast<double>(t_ns - t.vel_from_t) * 1e-9;
  if (t.vel_known && dt > 0 && dt < 0.1) {
    const double a = OneEuroFilter::alpha(kVelocityCutoffHz, dt);
    t.vel_u += a * ((u - t.vel_from_u) / dt - t.vel_u);
    t.vel_v += a * ((v - t.vel_from_v) / dt - t.vel_v);
  } else {
    t.vel_u = t.vel_v = 0;
  }
  t.vel_from_u = u;
  t.vel_from_v = v;
  t.vel_from_t = t_ns;
  t.vel_known = true;
}

void GazePipeline::track_valid(EyeTrack& t, EyeEvents& ev, glm::vec3 d, TimeNs t_ns) {
  const double ts = static_cast<double>(t_ns) * 1e-9;
  const double u = d.x / -d.z, v = d.y / -d.z;
  // Speeds: over the last interval (reacts at once to an onset, but noisy: tens of
  // deg/s at 0.5 deg noise, so it only gates the deviation test) and over the last two
  // (half the noise: decides when a saccade has landed).
  auto speed_since = [&](int k) {
    if (t.raw_count <= k) return 0.0;
    const double dt = static_cast<double>(t_ns - t.raw_t[k]) * 1e-9;
    return (dt > 0 && dt < 0.1) ? chord_deg(d, t.raw[k]) / dt : 0.0;
  };
  const double speed = speed_since(0);
  const bool returning = !t.ever_valid || static_cast<double>(t_ns - t.last_valid_t) > cfg_.hold_ms * 1e6;
  t.raw[1] = t.raw[0];
  t.raw_t[1] = t.raw_t[0];
  t.raw[0] = d;
  t.raw_t[0] = t_ns;
  t.raw_count = std::min(t.raw_count + 1, 2);
  t.last_valid_t = t_ns;
  t.ever_valid = true;
  t.confidence = 1.0f;

  if (returning || !t.u.initialised()) {  // first sample, or back after a loss: snap
    snap(t, u, v, t_ns);
    t.mode = Mode::fixation;
    t.state = FoveaState::fixation;
    return;
  }

  if (cfg_.saccade_aware) {
    if (t.mode == Mode::saccade) {
      if (speed_since(1) < cfg_.saccade_end_velocity_deg_s) {
        snap(t, u, v, t_ns);  // landed: settle from here
        t.mode = Mode::fixation;
        t.deviating = 0;
        t.state = FoveaState::fixation;
      } else {
        t.out_u = u;
        t.out_v = v;
        t.state = FoveaState::saccade;
      }
      return;
    }
    // Distance from the smoothed gaze. In pursuit the filter trails the target by up to
    // about a degree, so the bar is raised there to keep pursuit from looking like saccades.
    const double dev = chord_deg(d, unit_from_tangent(t.u.value(), t.v.value())) /
                       (t.mode == Mode::pursuit ? cfg_.pursuit_deviation_factor : 1.0);
    if (dev > cfg_.saccade_deviation_deg && (speed > cfg_.saccade_velocity_deg_s || t.mode == Mode::candidate)) {
      if (t.mode != Mode::candidate) t.candidate_t = t_ns;
      ++t.deviating;
      if (t.deviating >= cfg_.saccade_min_samples) {
        t.mode = Mode::saccade;
        ev.saccade_onset = true;
        ev.onset_t_ns = t.candidate_t;
      } else {
        t.mode = Mode::candidate;
      }
      // No smoothing lag at onset: show the raw gaze (vision is suppressed anyway).
      t.out_u = u;
      t.out_v = v;
      t.state = FoveaState::saccade;
      return;
    }
    if (t.mode == Mode::candidate) t.mode = Mode::fixation;  // a lone outlier: ignored
    t.deviating = 0;
  }

  // Fixation or pursuit.
  t.out_u = t.u.filter(u, ts, rate_hz_);
  t.out_v = t.v.filter(v, ts, rate_hz_);
  track_velocity(t, t_ns);
  ev.smoothed = true;
  // (sqrt, not std::hypot: this is the hot path and overflow cannot happen here)
  const double filtered_speed = std::sqrt(t.u.speed() * t.u.speed() + t.v.speed() * t.v.speed()) * kDegPerRad;
  t.pursuit_count = filtered_speed > cfg_.pursuit_velocity_deg_s ? t.pursuit_count + 1 : 0;
  t.mode = t.pursuit_count >= 3 ? Mode::pursuit : Mode::fixation;
  if (t.mode == Mode::pursuit && cfg_.predict_ms > 0) {  // latency compensation: extrapolate
    t.out_u += t.u.speed() * cfg_.predict_ms * 1e-3;
    t.out_v += t.v.speed() * cfg_.predict_ms * 1e-3;
  }
  t.state = t.mode == Mode::pursuit ? FoveaState::pursuit : FoveaState::fixation;
}

FoveaPoint GazePipeline::to_point(Eye e, double u, double v, FoveaState st, float conf) const {
  FoveaPoint p;
  p.state = st;
  p.confidence = conf;
  const EyeFrustum& f = model_.eye(e);
  // Tangent plane -> viewport pixels (docs/conventions.md), clamped inside the viewport.
  const double x = (u - f.tan_left) / (f.tan_right - f.tan_left) * model_.eye_width;
  const double y = (f.tan_top - v) / (f.tan_top - f.tan_bottom) * model_.eye_height;
  const float w = static_cast<float>(model_.eye_width), h = static_cast<float>(model_.eye_height);
  p.px.x = std::isfinite(x) ? std::clamp(static_cast<float>(x), 0.0f, std::nextafter(w, 0.0f)) : 0.5f * w;
  p.px.y = std::isfinite(y) ? std::clamp(static_cast<float>(y), 0.0f, std::nextafter(h, 0.0f)) : 0.5f * h;
  return p;
}

glm::vec2 GazePipeline::velocity_px(Eye e, const EyeTrack& t) const {
  // Tangent plane -> pixels is linear (to_point): the same scale applies to velocities.
  const EyeFrustum& f = model_.eye(e);
  const double sx = model_.eye_width / static_cast<double>(f.tan_right - f.tan_left);
  const double sy = -model_.eye_height / static_cast<double>(f.tan_top - f.tan_bottom);
  const glm::vec2 vpx{static_cast<float>(t.vel_u * sx), static_cast<float>(t.vel_v * sy)};
  return std::isfinite(vpx.x) && std::isfinite(vpx.y) ? vpx : glm::vec2{0.0f};
}

FoveaFrame GazePipeline::update(const GazeSample& s) {
  FoveaFrame f;
  f.t_ns = s.t_ns;
  std::array<bool, 2> valid{};
  for (Eye e : kEyes) {
    const auto i = static_cast<std::size_t>(e);
    events_[i] = EyeEvents{};
    glm::vec3 d;
    valid[i] = validate(s.eye(e), e, d);
    events_[i].valid = valid[i];
    if (valid[i]) track_valid(eyes_[i], events_[i], d, s.t_ns);
  }
  // Vergence: how far apart the eyes look while both fixate, for the other-eye fallback.
  if (valid[0] && valid[1] && eyes_[0].mode == Mode::fixation && eyes_[1].mode == Mode::fixation) {
    const double du = eyes_[0].out_u - eyes_[1].out_u, dv = eyes_[0].out_v - eyes_[1].out_v;
    if (!have_vergence_) {
      vergence_u_ = du;
      vergence_v_ = dv;
      have_vergence_ = true;
    } else {
      vergence_u_ += 0.05 * (du - vergence_u_);
      vergence_v_ += 0.05 * (dv - vergence_v_);
    }
  }
  for (Eye e : kEyes) {
    const auto i = static_cast<std::size_t>(e), o = 1 - i;
    EyeTrack& t = eyes_[i];
    if (!valid[i]) {
      const double gap_ms = static_cast<double>(s.t_ns - t.last_valid_t) * 1e-6;
      t.mode = Mode::fixation;
      t.deviating = 0;
      if (t.ever_valid && gap_ms <= cfg_.hold_ms) {
        // A blink or a dropout: hold the last fixation, losing confidence as it ages.
        t.state = FoveaState::blink;
        t.confidence = static_cast<float>(0.5 * (1.0 - gap_ms / std::max(cfg_.hold_ms, 1.0)));
      } else if (valid[o]) {
        const double sign = i == 0 ? 1.0 : -1.0;  // left = right + vergence
        t.out_u = eyes_[o].out_u + sign * (have_vergence_ ? vergence_u_ : 0.0);
        t.out_v = eyes_[o].out_v + sign * (have_vergence_ ? vergence_v_ : 0.0);
        t.state = eyes_[o].state;
        t.confidence = 0.5f * eyes_[o].confidence;
      } else {
        t.out_u = centre_u_[i];
        t.out_v = centre_v_[i];
        t.state = FoveaState::lost;
        t.confidence = 0.0f;
      }
    }
    events_[i].u = t.out_u;
    events_[i].v = t.out_v;
    f.eyes[i] = to_point(e, t.out_u, t.out_v, t.state, t.confidence);
    // Safe to extrapolate only what the 1€ smoothed on this eye's own sample.
    if (valid[i] && events_[i].smoothed) {
      f.eyes[i].predictable = true;
      f.eyes[i].velocity_px_s = velocity_px(e, t);
      // In pursuit the 1€ trails the eye by its ramp lag; made up for there only: in a
      // fixation the "lag" is the noise the filter removed (measured, docs/filtering.md).
      if (t.state == FoveaState::pursuit) {
        const double lag_u = std::min(t.u.ramp_lag_s(), kMaxLagS), lag_v = std::min(t.v.ramp_lag_s(), kMaxLagS);
        const glm::vec2 lag = f.eyes[i].velocity_px_s * glm::vec2(static_cast<float>(lag_u), static_cast<float>(lag_v));
        if (std::isfinite(lag.x) && std::isfinite(lag.y)) f.eyes[i].lag_px = lag;
      }
    }
  }
  return f;
}

}  // namespace foveal
