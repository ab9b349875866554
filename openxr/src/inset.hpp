#pragma once
// The quad views' geometry, as plain arithmetic on fields of view (no OpenXR calls):
// where the inner view lies inside the outer one for a gaze, how it moves between the
// gaze-following inset and the fixed one, and the views' recommended sizes from the
// user's EFR pair. docs/openxr.md, "Quad views".
#include <openxr/openxr.h>

#include <cstdint>

namespace foveal::openxr {

/// The inset's settings (docs/openxr.md lists their environment keys and defaults).
struct InsetSettings {
  /// The inner view's size as a share of the outer view's tangent extent, per axis:
  /// gaze-following, and fixed at the centre (no gaze, or foveation off).
  float foveated_share_x = 0.35f, foveated_share_y = 0.35f;
  float fixed_share_x = 0.5f, fixed_share_y = 0.45f;
  /// Width of the band over which the inner view is blended onto the outer one (degrees).
  float blend_deg = 3.0f;
  /// How long the inset takes to move between the gaze and the fixed place (ms).
  float transition_ms = 150.0f;
};

/// Reads FOVEAL_OPENXR_INSET (share, or share_x,share_y), FOVEAL_OPENXR_FIXED_INSET,
/// FOVEAL_OPENXR_BLEND_DEG; a malformed value keeps the default and sets `problem`.
InsetSettings inset_settings_from_environment(const char** problem);

/// A field of view as the tangents of its four half-angles (left and down negative).
struct TanRect {
  float left, right, down, up;
};
TanRect to_tangents(const XrFovf& f);
XrFovf to_fov(const TanRect& t);

/// The inset of `share` of the outer view's extent centred on the tangent point (cx, cy),
/// moved inward where it would cross the outer view's edges, so that it always lies
/// inside it (strictly: by a margin of 1e-4 of the extent).
TanRect place_inset(const TanRect& outer, float share_x, float share_y, float cx, float cy);

/// One eye's inset as it moves: `follow` in [0, 1] (1 on the gaze, 0 fixed) eases toward
/// its target over transition_ms of display time, and the last gaze is held while it
/// eases away, so neither a lost gaze nor its return makes the inset jump.
class InsetMotion {
 public:
  /// The inner view for `display_time` (ns). gaze_valid: the gaze point (tangents in the
  /// outer view's frame) is current. Calls with the same time give the same answer.
  TanRect update(const TanRect& outer, const InsetSettings& s, bool gaze_valid, float gx, float gy,
                 std::int64_t display_time);
  float follow() const { return follow_; }

 private:
  float follow_ = 0.0f;
  float gx_ = 0.0f, gy_ = 0.0f;
  bool have_gaze_ = false;
  std::int64_t last_time_ = 0;
};

/// Recommended image sizes of the four views from the runtime's stereo view sizes.
/// density[e]: the outer view's density for eye e (1/σ of the eye's EFR level);
/// the inner views at full density over the inset's share of the extent.
struct QuadSizes {
  std::uint32_t width[4], height[4];
};
QuadSizes quad_sizes(const std::uint32_t stereo_w[2], const std::uint32_t stereo_h[2], const float density[2],
                     float share_x, float share_y);

}  // namespace foveal::openxr
