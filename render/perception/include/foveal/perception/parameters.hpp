#pragma once
// FovVideoVDP's fitted values (docs/metrics.md, "JOD"). The defaults are the calibration of
// the reference's release 1.2 (20/11/2021), the one its shipped CSF tables belong to; the
// paper's own fit (release 1.0) differs in the masking, pooling and JOD values.

namespace foveal::perception {

struct Parameters {
  double mask_p = 2.4;              ///< exponent of the masked contrast difference
  double mask_c = -0.973838;        ///< log10 of the masking signal's gain
  double mask_q_sustained = 2.43685;   ///< masking exponent, sustained channel
  double mask_q_transient = 4.946;     ///< masking exponent, transient channel
  double beta = 1.52134;            ///< spatial pooling (p-norm over a band)
  double beta_tch = 0.666092;       ///< pooling over the two temporal channels
  double w_transient = 0.25;        ///< weight of the transient channel
  double sensitivity_correction_db = 16.2596;  ///< CSF gain, 20·log10
  double jod_a = -0.0161713;        ///< JOD regression: 10 + a·Q^(10^log_jod_exp)
  double log_jod_exp = -0.2280;
  double k_cm = 0.604562;           ///< cortical magnification exponent
  double csf_sigma = -1.5;          ///< stimulus size: 1.5 cycles (negative: in cycles)
  double sustained_sigma = 0.5;     ///< log-normal sustained impulse response
  double sustained_beta_s = 0.06;   ///< its peak time, seconds
  double transient_omega_hz = 5.0;  ///< temporal frequency the transient channel's CSF is taken at

  /// The calibration of the reference's release 1.0 (18/04/2021), the paper's release.
  static Parameters release_1_0() {
    Parameters p;
    p.mask_c = -0.544583;
    p.beta = 0.95753;
    p.beta_tch = 0.684842;
    p.sensitivity_correction_db = 10;
    p.jod_a = -0.249449;
    p.log_jod_exp = -0.4289;
    p.mask_q_sustained = 3.23726;
    p.mask_q_transient = 3.02625;
    p.k_cm = 0.405835;
    return p;
  }
};

}  // namespace foveal::perception
