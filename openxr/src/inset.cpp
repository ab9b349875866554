#include "inset.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

namespace foveal::openxr {

namespace {

/// "a" or "a,b", each in (0, 1].
bool parse_shares(const char* text, float& x, float& y) {
  char* end = nullptr;
  const float a = std::strtof(text, &end);
  float b = a;
  if (end == text) return false;
  if (*end == ',') {
    const char* second = end + 1;
    b = std::strtof(second, &end);
    if (end == second) return false;
  }
  if (*end != '\0' || !(a > 0.0f && a <= 1.0f) || !(b > 0.0f && b <= 1.0f)) return false;
  x = a;
  y = b;
  return true;
}

}  // namespace

InsetSettings inset_settings_from_environment(const char** problem) {
  InsetSettings s;
  *problem = nullptr;
  if (const char* v = std::getenv("FOVEAL_OPENXR_INSET"); v && *v &&
      !parse_shares(v, s.foveated_share_x, s.foveated_share_y))
    *problem = "FOVEAL_OPENXR_INSET must be a share of the view in (0, 1], or two (x,y): using 0.35";
  if (const char* v = std::getenv("FOVEAL_OPENXR_FIXED_INSET"); v && *v &&
      !parse_shares(v, s.fixed_share_x, s.fixed_share_y))
    *problem = "FOVEAL_OPENXR_FIXED_INSET must be a share of the view in (0, 1], or two (x,y): using 0.5,0.45";
  if (const char* v = std::getenv("FOVEAL_OPENXR_BLEND_DEG"); v && *v) {
    char* end = nullptr;
    const float d = std::strtof(v, &end);
    if (*end != '\0' || !(d >= 0.0f && d <= 20.0f))
      *problem = "FOVEAL_OPENXR_BLEND_DEG must be 0 to 20 degrees: using 3";
    else
      s.blend_deg = d;
  }
  return s;
}

TanRect to_tangents(const XrFovf& f) {
  return {std::tan(f.angleLeft), std::tan(f.angleRight), std::tan(f.angleDown), std::tan(f.angleUp)};
}

XrFovf to_fov(const TanRect& t) { return {std::atan(t.left), std::atan(t.right), std::atan(t.up), std::atan(t.down)}; }

TanRect place_inset(const TanRect& outer, float share_x, float share_y, float cx, float cy) {
  const float w = outer.right - outer.left, h = outer.up - outer.down;
  const float margin_x = 1e-4f * w, margin_y = 1e-4f * h;
  const float hw = std::min(0.5f * share_x * w, 0.5f * w - margin_x);
  const float hh = std::min(0.5f * share_y * h, 0.5f * h - margin_y);
  if (!std::isfinite(cx) || !std::isfinite(cy)) cx = cy = 0.0f;
  cx = std::clamp(cx, outer.left + margin_x + hw, outer.right - margin_x - hw);
  cy = std::clamp(cy, outer.down + margin_y + hh, outer.up - margin_y - hh);
  return {cx - hw, cx + hw, cy - hh, cy + hh};
}

TanRect InsetMotion::update(const TanRect& outer, const InsetSettings& s, bool gaze_valid, float gx, float gy,
                            std::int64_t display_time) {
  if (gaze_valid) gx_ = gx, gy_ = gy, have_gaze_ = true;
  const float target = gaze_valid ? 1.0f : 0.0f;
  if (last_time_ == 0) {
    follow_ = target;  // the first frame starts where it is
  } else if (display_time > last_time_) {
    // The step saturates: a long pause (or a time far ahead) is a whole transition, and
    // the subtraction cannot overflow for display times of a running session.
    const double dt_ms = static_cast<double>(std::min<std::int64_t>(display_time - last_time_, 10'000'000'000)) / 1e6;
    const float step = s.transition_ms > 0 ? static_cast<float>(dt_ms / s.transition_ms) : 1.0f;
    follow_ = follow_ < target ? std::min(target, follow_ + step) : std::max(target, follow_ - step);
  }
  if (display_time > last_time_) last_time_ = display_time;
  const TanRect fixed = place_inset(outer, s.fixed_share_x, s.fixed_share_y, 0.5f * (outer.left + outer.right),
                                    0.5f * (outer.down + outer.up));
  if (!have_gaze_ || follow_ <= 0.0f) return fixed;
  const TanRect on_gaze = place_inset(outer, s.foveated_share_x, s.foveated_share_y, gx_, gy_);
  if (follow_ >= 1.0f) return on_gaze;
  // Smoothstep in time; both ends lie inside the outer view, and so does every mix.
  const float a = follow_ * follow_ * (3.0f - 2.0f * follow_);
  auto mix = [a](float f, float g) { return f + a * (g - f); };
  return {mix(fixed.left, on_gaze.left), mix(fixed.right, on_gaze.right), mix(fixed.down, on_gaze.down),
          mix(fixed.up, on_gaze.up)};
}

QuadSizes quad_sizes(const std::uint32_t stereo_w[2], const std::uint32_t stereo_h[2], const float density[2],
                     float share_x, float share_y) {
  QuadSizes q{};
  auto scaled = [](std::uint32_t n, float k) {
    return std::max<std::uint32_t>(16, static_cast<std::uint32_t>(std::lround(static_cast<double>(n) * k)));
  };
  for (int e = 0; e < 2; ++e) {
    const float d = std::clamp(density[e], 1.0f / 16.0f, 1.0f);
    q.width[e] = scaled(stereo_w[e], d);
    q.height[e] = scaled(stereo_h[e], d);
    q.width[e + 2] = scaled(stereo_w[e], share_x);
    q.height[e + 2] = scaled(stereo_h[e], share_y);
  }
  return q;
}

}  // namespace foveal::openxr
