#pragma once
// The 1€ filter (Casiez et al. 2012): a first-order low-pass whose cutoff rises with
// speed, so it smooths fixations and follows movement. Matches the reference
// implementation (tests/filter/data): the speed comes from the last *filtered*
// value, the first output is the first input.
#include <algorithm>
#include <cmath>
#include <numbers>

namespace foveal {

struct OneEuroParams {
  double min_cutoff_hz = 1.0;
  double beta = 0.0;
  double d_cutoff_hz = 1.0;
};

class OneEuroFilter {
 public:
  OneEuroFilter() = default;
  explicit OneEuroFilter(OneEuroParams p) : p_(p) {}
  /// Filters `x` at time `t_s` (seconds); `rate_hz` is used when no previous time exists.
  double filter(double x, double t_s, double rate_hz) {
    if (!init_) {
      init_ = true;
      x_hat_ = x;
      dx_hat_ = 0.0;
      t_prev_ = t_s;
      return x;
    }
    const double dt = t_s > t_prev_ ? t_s - t_prev_ : 1.0 / rate_hz;
    t_prev_ = t_s;
    const double dx = (x - x_hat_) / dt;
    dx_hat_ += alpha(p_.d_cutoff_hz, dt) * (dx - dx_hat_);
    const double cutoff = p_.min_cutoff_hz + p_.beta * std::fabs(dx_hat_);
    double a = alpha(cutoff, dt);
    if (settle_k_ > 0) a = std::max(a, 1.0 / static_cast<double>(++settle_k_));  // settling: a running mean
    x_hat_ += a * (x - x_hat_);
    last_a_ = a;
    last_dt_ = dt;
    return x_hat_;
  }
  /// Starts over at `x` (a saccade's landing point): no memory of the old fixation.
  /// With `settle`, the next samples are averaged (weight 1/k for the k-th) for as long
  /// as that smooths less than the filter itself would: the fastest unbiased settling.
  void reset(double x, double t_s, bool settle = false) {
    init_ = true;
    x_hat_ = x;
    dx_hat_ = 0.0;
    t_prev_ = t_s;
    settle_k_ = settle ? 1 : 0;
    last_a_ = 0;
  }
  bool initialised() const { return init_; }
  double value() const { return x_hat_; }
  double speed() const { return dx_hat_; }  ///< filtered derivative, units per second
  /// How far the output trails a steady ramp at the last step's weight a and interval
  /// dt (seconds): the exponential smoother's steady-state lag, dt (1 - a) / a. 0 before
  /// the first step after a start or reset.
  double ramp_lag_s() const { return last_a_ > 0 ? last_dt_ * (1.0 - last_a_) / last_a_ : 0.0; }
  void set_params(const OneEuroParams& p) { p_ = p; }

  static double alpha(double cutoff_hz, double dt) {
    const double tau = 1.0 / (2.0 * std::numbers::pi * cutoff_hz);
    return 1.0 / (1.0 + tau / dt);
  }

 private:
  OneEuroParams p_;
  bool init_ = false;
  double x_hat_ = 0, dx_hat_ = 0, t_prev_ = 0;
  int settle_k_ = 0;  ///< > 0 while settling after a reset
  double last_a_ = 0, last_dt_ = 0;  ///< the last step's weight and interval (ramp_lag_s)
};

}  // namespace foveal
