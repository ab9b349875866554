#pragma once
// Every parameter of the gaze pipeline in one place (docs/filtering.md); profiles
// override it through their "filter" object. validate() runs when a config is loaded,
// never in the per-sample path.
#include <string>

#include <nlohmann/json.hpp>

#include "foveal/core/error.hpp"
#include "foveal/runtime/one_euro.hpp"

namespace foveal {

struct FilterConfig {
  // Validation.
  double min_openness = 0.1;          ///< an eye less open than this is treated as closed
  double unit_tolerance = 0.05;       ///< | |dir| - 1 | above this: not a unit vector, invalid
  double fov_margin_deg = 10.0;       ///< directions this far outside the display's FOV are invalid
  // Blinks and dropouts.
  double hold_ms = 250.0;             ///< hold the last fixation this long, then fall back
  // Saccades (I-VT with a deviation test, on each eye's own gaze).
  double saccade_velocity_deg_s = 70.0;  ///< onset: sample-to-sample speed above this ...
  double saccade_deviation_deg = 1.2;    ///< ... and this far from the fixation estimate
  double pursuit_deviation_factor = 1.6; ///< in pursuit the deviation must be this many times larger
  double saccade_end_velocity_deg_s = 60.0;  ///< the saccade ends when the speed falls below
  int saccade_min_samples = 2;        ///< onset confirmed after this many deviating samples
  // Smoothing (1€ on azimuth and elevation, degrees) and its settling after a saccade.
  OneEuroParams one_euro{0.3, 0.1, 1.0};
  bool saccade_aware = true;          ///< false: plain 1€ everywhere (for charts)
  // Pursuit and latency compensation.
  double pursuit_velocity_deg_s = 12.0;  ///< filtered speed above this in a fixation: pursuit
  double predict_ms = 0.0;            ///< predict forward this far in pursuit (0 = off)

  Status validate(const std::string& where) const;
  nlohmann::json to_json() const;
  /// Defaults overridden by the keys present; unknown keys and bad values are errors.
  static Result<FilterConfig> from_json(const nlohmann::json& j, const std::string& where);
};

}  // namespace foveal
