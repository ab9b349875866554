#pragma once
// Raw gaze samples -> a stable, fast fovea point per eye (docs/filtering.md):
// validation, blink/dropout fallbacks, saccade detection, saccade-aware 1€ smoothing,
// optional prediction, and the display model's direction -> pixel mapping.
#include <array>
#include <cmath>

#include <glm/vec3.hpp>

#include "foveal/core/display_model.hpp"
#include "foveal/runtime/filter_config.hpp"
#include "foveal/runtime/fovea.hpp"

namespace foveal {

/// What happened in one eye on the last update (for traces, charts and tests).
struct EyeEvents {
  bool valid = false;            ///< the sample passed validation
  bool smoothed = false;         ///< the output came from the 1€ (fixation or pursuit), not raw or a fallback
  bool saccade_onset = false;    ///< a saccade was confirmed on this sample ...
  TimeNs onset_t_ns = 0;         ///< ... and began at this sample's time
  double u = 0, v = 0;           ///< the output gaze on the tangent plane (x/-z, y/-z)
  /// The output gaze as a unit direction in the eye frame.
  glm::vec3 direction() const {
    const double n = 1.0 / std::sqrt(u * u + v * v + 1.0);
    return {static_cast<float>(u * n), static_cast<float>(v * n), static_cast<float>(-n)};
  }
};

/// One instance per gaze stream; not thread-safe (the gaze thread owns it). A config
/// must be validated before it gets here: update() never fails.
class GazePipeline {
 public:
  GazePipeline(DisplayModel model, FilterConfig config);
  FoveaFrame update(const GazeSample& s);
  const EyeEvents& events(Eye e) const { return events_[static_cast<std::size_t>(e)]; }
  const DisplayModel& model() const { return model_; }
  const FilterConfig& config() const { return cfg_; }
  void reset();

 private:
  enum class Mode { fixation, candidate, saccade, pursuit };
  struct EyeTrack {
    OneEuroFilter u, v;               ///< on the eye's tangent plane (x/-z, y/-z)
    Mode mode = Mode::fixation;
    int raw_count = 0;                 ///< valid samples in raw history (0..2)
    glm::vec3 raw[2]{};                ///< last and second-to-last unit directions
    TimeNs raw_t[2] = {0, 0};
    TimeNs last_valid_t = 0, candidate_t = 0;
    bool ever_valid = false;
    int deviating = 0, pursuit_count = 0;
    double out_u = 0, out_v = 0;      ///< output on the tangent plane
    /// Velocity of the smoothed gaze (tangent units/s): the 1€ output's derivative,
    /// low-passed; restarts at every snap. What predict_fovea extrapolates.
    double vel_u = 0, vel_v = 0;
    double vel_from_u = 0, vel_from_v = 0;  ///< the smoothed gaze it was last taken from
    TimeNs vel_from_t = 0;
    bool vel_known = false;
    FoveaState state = FoveaState::lost;
    float confidence = 0;
  };

  bool validate(const EyeSample& e, Eye eye, glm::vec3& unit) const;
  void track_valid(EyeTrack& t, EyeEvents& ev, glm::vec3 d, TimeNs t_ns);
  void snap(EyeTrack& t, double u, double v, TimeNs t_ns);
  void track_velocity(EyeTrack& t, TimeNs t_ns) const;
  FoveaPoint to_point(Eye e, double u, double v, FoveaState st, float conf) const;
  glm::vec2 velocity_px(Eye e, const EyeTrack& t) const;

  DisplayModel model_;
  FilterConfig cfg_;
  double rate_hz_ = 120.0;
  std::array<EyeTrack, 2> eyes_;
  std::array<EyeEvents, 2> events_;
  double vergence_u_ = 0, vergence_v_ = 0;  ///< left minus right, in fixations
  bool have_vergence_ = false;
  std::array<EyeFrustum, 2> valid_box_{};     ///< the frustum widened by fov_margin_deg
  std::array<double, 2> centre_u_{}, centre_v_{};
};

}  // namespace foveal
