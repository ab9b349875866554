#include "foveal/runtime/filter_config.hpp"

#include <algorithm>
#include <cmath>

namespace foveal {

namespace {

Status positive(double v, const std::string& where, const char* key) {
  if (!std::isfinite(v) || v <= 0) return bad_input(where + ": filter." + key + ": must be a number > 0");
  return {};
}
Status non_negative(double v, const std::string& where, const char* key) {
  if (!std::isfinite(v) || v < 0) return bad_input(where + ": filter." + key + ": must be a number >= 0");
  return {};
}

}  // namespace

Status FilterConfig::validate(const std::string& where) const {
  if (!(min_openness >= 0 && min_openness < 1)) return bad_input(where + ": filter.min_openness: must be in [0, 1)");
  for (auto [v, k] : {std::pair{unit_tolerance, "unit_tolerance"}, std::pair{saccade_velocity_deg_s, "saccade_velocity_deg_s"},
                      std::pair{saccade_deviation_deg, "saccade_deviation_deg"},
                      std::pair{pursuit_deviation_factor, "pursuit_deviation_factor"},
                      std::pair{saccade_end_velocity_deg_s, "saccade_end_velocity_deg_s"},
                      std::pair{one_euro.min_cutoff_hz, "min_cutoff_hz"}, std::pair{one_euro.d_cutoff_hz, "d_cutoff_hz"},
                      std::pair{pursuit_velocity_deg_s, "pursuit_velocity_deg_s"}})
    if (Status s = positive(v, where, k); !s) return s;
  for (auto [v, k] : {std::pair{fov_margin_deg, "fov_margin_deg"}, std::pair{hold_ms, "hold_ms"},
                      std::pair{one_euro.beta, "beta"}, std::pair{predict_ms, "predict_ms"}})
    if (Status s = non_negative(v, where, k); !s) return s;
  if (saccade_min_samples < 1 || saccade_min_samples > 10)
    return bad_input(where + ": filter.saccade_min_samples: must be in 1..10");
  if (predict_ms > 100) return bad_input(where + ": filter.predict_ms: at most 100 ms");
  return {};
}

nlohmann::json FilterConfig::to_json() const {
  return {{"min_openness", min_openness},
          {"unit_tolerance", unit_tolerance},
          {"fov_margin_deg", fov_margin_deg},
          {"hold_ms", hold_ms},
          {"saccade_velocity_deg_s", saccade_velocity_deg_s},
          {"saccade_deviation_deg", saccade_deviation_deg},
          {"pursuit_deviation_factor", pursuit_deviation_factor},
          {"saccade_end_velocity_deg_s", saccade_end_velocity_deg_s},
          {"saccade_min_samples", saccade_min_samples},
          {"min_cutoff_hz", one_euro.min_cutoff_hz},
          {"beta", one_euro.beta},
          {"d_cutoff_hz", one_euro.d_cutoff_hz},
          {"saccade_aware", saccade_aware},
          {"pursuit_velocity_deg_s", pursuit_velocity_deg_s},
          {"predict_ms", predict_ms}};
}

Result<FilterConfig> FilterConfig::from_json(const nlohmann::json& j, const std::string& where) {
  if (!j.is_object()) return bad_input(where + ": filter: expected an object");
  FilterConfig c;
  for (auto it = j.begin(); it != j.end(); ++it) {
    const std::string& k = it.key();
    const nlohmann::json& v = it.value();
    if (k == "saccade_aware") {
      if (!v.is_boolean()) return bad_input(where + ": filter.saccade_aware: expected true or false");
      c.saccade_aware = v.get<bool>();
      continue;
    }
    if (!v.is_number()) return bad_input(where + ": filter." + k + ": expected a number");
    const double d = v.get<double>();
    if (k == "min_openness") c.min_openness = d;
    else if (k == "unit_tolerance") c.unit_tolerance = d;
    else if (k == "fov_margin_deg") c.fov_margin_deg = d;
    else if (k == "hold_ms") c.hold_ms = d;
    else if (k == "saccade_velocity_deg_s") c.saccade_velocity_deg_s = d;
    else if (k == "saccade_deviation_deg") c.saccade_deviation_deg = d;
    else if (k == "pursuit_deviation_factor") c.pursuit_deviation_factor = d;
    else if (k == "saccade_end_velocity_deg_s") c.saccade_end_velocity_deg_s = d;
    else if (k == "saccade_min_samples") {
      if (d != std::floor(d)) return bad_input(where + ": filter.saccade_min_samples: expected an integer");
      c.saccade_min_samples = static_cast<int>(std::clamp(d, -1.0, 1000.0));
    } else if (k == "min_cutoff_hz") c.one_euro.min_cutoff_hz = d;
    else if (k == "beta") c.one_euro.beta = d;
    else if (k == "d_cutoff_hz") c.one_euro.d_cutoff_hz = d;
    else if (k == "pursuit_velocity_deg_s") c.pursuit_velocity_deg_s = d;
    else if (k == "predict_ms") c.predict_ms = d;
    else return bad_input(where + ": filter: unknown key '" + k + "'");
  }
  if (Status s = c.validate(where); !s) return s.error();
  return c;
}

}  // namespace foveal
