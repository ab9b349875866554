#pragma once
// Turns a HUTRR74 gaze point on the calibrated screen plane into per-eye gaze rays in
// the head frame (docs/conventions.md): each eye looks from its position to the point.
#include "foveal/core/gaze_sample.hpp"
#include "foveal/drivers/hid/tracker_reports.hpp"

namespace foveal::hid {

/// What the driver knows of the screen plane. Eye positions the tracker does not report
/// fall back to a nominal pair of eyes in front of the screen centre.
struct ScreenPlane {
  double width_mm = 0;            ///< calibrated screen width (0: unknown)
  double height_mm = 0;
  double viewing_distance_mm = 600;  ///< nominal eye distance (the optimum tracking distance)
  double ipd_mm = 63;                ///< nominal interpupillary distance

  /// From the Configuration and Capabilities reports, keeping defaults for what is 0.
  static ScreenPlane from(const TrackerConfiguration& config, const TrackerCapabilities& caps);
};

/// Fills directions (and origins, when the tracker reports eye positions) of both eyes
/// and the combined gaze. t_ns is left to the caller. With no valid gaze point, every
/// validity bit is clear.
GazeSample screen_gaze_to_sample(const TrackingData& data, const ScreenPlane& plane);

}  // namespace foveal::hid
