#pragma once
// Whether foveald's head poses follow the emulated headsets (vm_hmd.cpp): frames.csv's
// head columns against the motion script (hmd_motion.hpp), and the display-model file
// written from the emulated Vive's configuration against that configuration.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/clock.hpp"
#include "foveal/core/pose.hpp"

namespace foveal::vmtest {

struct HeadRow {
  std::uint64_t frame = 0;
  TimeNs t_ns = 0;       ///< the frame's fovea time
  TimeNs pose_t_ns = 0;  ///< the time the pose is for (head_t_ns; 0: the file has no such column)
  Pose pose{};
};
/// frames.csv's head columns (found by name in the header); `problem` says what is wrong.
std::vector<HeadRow> read_head_rows(const std::string& path, std::string& problem);

/// One line a row (times, position, heading, pitch, roll) for a failure's console log.
std::string describe_rows(const std::vector<HeadRow>& rows);

/// The tolerances (docs/vm-tests.md, vm_hmd_pose).
constexpr double kPositionTolM = 0.02, kAngleTolDeg = 2.0;
/// PS VR2: how much later than the time foveald names for it (head_t_ns) the time a
/// pose shows may be, and how much earlier. Late: foveald predicts at most 100 ms past
/// its newest measurement, and under emulation measurements arrive up to about half a
/// second late (a late one is placed at its arrival: DeviceClock). Early: prediction
/// overshooting.
constexpr double kPsvr2LateTolS = 1.0, kPsvr2EarlyTolS = 0.1;
/// Vive: the fitted yaw rate against the motion's, relative.
constexpr double kViveRateTol = 0.02;

struct FollowCheck {
  std::size_t rows = 0, checked = 0, bad = 0;
  double max_position_m = 0, max_angle_deg = 0, max_time_s = 0;
  double rate = 0;  ///< Vive: the fitted yaw rate (rad/s)
  std::string problem;
  std::string summary() const;
};

/// Which rows to check: those whose reference time (pose_t_ns, else t_ns) is in [from, to].
struct Window {
  TimeNs from = 0, to = 0;
};

/// PS VR2 (6DoF, absolute): each pose is the motion at some time t* (found from its
/// heading, the turn nearest the reference time): position and orientation within
/// tolerance of motion(t*), and t* within [head_t_ns - kPsvr2LateTolS, head_t_ns +
/// kPsvr2EarlyTolS] (without head_t_ns, within 1.5 s of the fovea time).
FollowCheck check_psvr2_rows(const std::vector<HeadRow>& rows, const std::vector<Window>& windows);

/// Vive (3DoF from the fused IMU, heading free): pitch and roll of every pose within
/// tolerance of the motion's, and in each window the heading against the reference time
/// a line whose slope is the motion's yaw rate (kViveRateTol) with residuals within
/// tolerance (a constant lag is absorbed by the line).
FollowCheck check_vive_rows(const std::vector<HeadRow>& rows, const std::vector<Window>& windows);

/// A display-model file against the emulated configuration (vive_pattern.hpp): size,
/// IPD, and the optics: over the panel points within the cutoff, the direction each
/// colour channel shows by the model's frustum and polynomial against the
/// configuration's (the intrinsics grown by grow_for_undistort, DISTORT_DPOLY3; both
/// written out here), rms and max in rendered pixels.
struct ModelCheck {
  bool pass = false;
  std::string details;
};
ModelCheck check_vive_model(const nlohmann::json& model);

}  // namespace foveal::vmtest
