#pragma once
// Third-party gaze exports -> the native gaze log (docs/importers.md).
#include <cstdint>
#include <string>

#include "foveal/core/error.hpp"

namespace foveal {

struct ImportSummary {
  std::string format;  ///< "sranipal" or "pupil"
  std::uint64_t rows = 0;
  std::uint64_t invalid[2] = {0, 0};  ///< per eye: samples without a valid direction
  double rate_hz = 0;                 ///< nominal rate written into the header
  bool head_pose = false;             ///< the input had head poses: the log is v2 with them
};

/// HTC SRanipal CSV (semicolon, 100 ns ticks, validity bitmask). SRanipal's frame is
/// x left, y up, +z forward; foveal's is x right, y up, -z forward: x and z flip
/// (a 180 degree turn about y), for directions and origins alike. With the headset
/// columns (helmet_pos_* in metres, helmet_rot_* Unity Euler angles in degrees, all six
/// or none) every sample gets the head pose and the log is v2; without them, v1.
Result<ImportSummary> import_sranipal(const std::string& in, const std::string& out);

/// Pupil Labs gaze_positions.csv. Camera frame x right, y down, +z forward: y and z
/// flip. gaze_normal0 is the right eye, gaze_normal1 the left (Pupil Core naming).
/// Rows with confidence < 0.6 are invalid for both eyes.
Result<ImportSummary> import_pupil(const std::string& in, const std::string& out);

}  // namespace foveal
