#pragma once
// Decodes the HUTRR74 tracker reports into plain values in millimetres, hertz and
// nanoseconds, and encodes the Mode Request. Lengths are taken from the layout; every
// malformed report comes back as an error naming the report and what is wrong.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "foveal/core/error.hpp"
#include "foveal/drivers/hid/tracker_layout.hpp"

namespace foveal::hid {

/// Capabilities feature report (0x12:0x11). Distances in mm; 0 when absent.
struct TrackerCapabilities {
  int tracker_quality = 0;
  double minimum_distance_mm = 0, optimum_distance_mm = 0, maximum_distance_mm = 0;
  double max_screen_width_mm = 0, max_screen_height_mm = 0;
};

/// Configuration feature report (0x12:0x12): the calibrated screen plane.
struct TrackerConfiguration {
  std::uint32_t display_manufacturer_id = 0, display_product_id = 0, display_serial = 0, display_date = 0;
  double screen_width_mm = 0, screen_height_mm = 0;
};

/// Tracker Status report (0x12:0x13), feature or input.
struct TrackerStatus {
  int configuration_status = 0;  ///< 1 ready, 2 configuring, 3 screen setup needed, 4 calibration needed
  double sampling_frequency_hz = 0;
};

/// Tracking Data input report (0x12:0x10). Positions in mm on the calibrated screen
/// plane's frame (origin top-left, x right, y down, z towards the user; docs/hid.md).
struct TrackingData {
  std::optional<std::int64_t> device_time_ns;  ///< the report's Timestamp, if it has one
  bool gaze_valid = false;
  double gaze_x_mm = 0, gaze_y_mm = 0;
  bool left_valid = false, right_valid = false;
  glm::dvec3 left_eye_mm{0.0}, right_eye_mm{0.0};
};

const char* configuration_status_name(int status);

Result<TrackingData> decode_tracking_data(const TrackerLayout& l, std::span<const std::uint8_t> report);
Result<TrackerStatus> decode_status(const TrackerLayout& l, ReportType type, std::span<const std::uint8_t> report);
Result<TrackerCapabilities> decode_capabilities(const TrackerLayout& l, std::span<const std::uint8_t> report);
Result<TrackerConfiguration> decode_configuration(const TrackerLayout& l, std::span<const std::uint8_t> report);

/// The Tracker Control feature report asking for `mode` (kModeGazePoint | ...).
Result<std::vector<std::uint8_t>> encode_mode_request(const TrackerLayout& l, std::uint8_t mode);

}  // namespace foveal::hid
