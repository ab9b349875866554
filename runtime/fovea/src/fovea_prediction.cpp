#include "foveal/runtime/fovea_prediction.hpp"

#include <algorithm>
#include <cmath>

namespace foveal {

FoveaFrame predict_fovea(const FoveaFrame& f, TimeNs display_t_ns, int eye_w, int eye_h, const FoveaPrediction& p) {
  if (!p.enabled || eye_w <= 0 || eye_h <= 0) return f;
  // Subtract in floating point: a garbage display time cannot overflow the difference.
  const double want_s = (static_cast<double>(display_t_ns) - static_cast<double>(f.t_ns)) * 1e-9;
  const double max_s = static_cast<double>(std::max<TimeNs>(p.max_horizon_ns, 0)) * 1e-9;
  const double h = std::clamp(want_s, 0.0, max_s);
  if (!(h > 0)) return f;
  const float w = static_cast<float>(eye_w), hh = static_cast<float>(eye_h);
  FoveaFrame out = f;
  for (FoveaPoint& e : out.eyes) {
    if (!e.predictable) continue;
    const double x = static_cast<double>(e.px.x) + e.lag_px.x + static_cast<double>(e.velocity_px_s.x) * h;
    const double y = static_cast<double>(e.px.y) + e.lag_px.y + static_cast<double>(e.velocity_px_s.y) * h;
    if (!std::isfinite(x) || !std::isfinite(y)) continue;
    // Clamped before the cast: a double beyond float's range does not convert.
    e.px.x = static_cast<float>(std::clamp(x, 0.0, static_cast<double>(std::nextafter(w, 0.0f))));
    e.px.y = static_cast<float>(std::clamp(y, 0.0, static_cast<double>(std::nextafter(hh, 0.0f))));
  }
  return out;
}

}  // namespace foveal
