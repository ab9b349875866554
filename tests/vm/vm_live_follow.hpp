#pragma once
// Whether foveald's fovea follows the emulated device (vm_live.cpp): the device's
// deterministic reports (feeder_pattern.hpp, psvr2_pattern.hpp) replayed through the
// gaze pipeline foveald runs, against its trace.csv.
#include <functional>
#include <string>
#include <vector>

#include "foveal/core/error.hpp"
#include "foveal/core/gaze_sample.hpp"
#include "vm_live_files.hpp"

namespace foveal::vmtest {

/// What one kind of device needs here: its presence, and the sample its k-th report makes.
struct LiveDevice {
  std::function<bool()> present;
  std::function<GazeSample(std::uint64_t k)> sample;
  std::uint64_t period = 0;  ///< sample(k) repeats with this period in k
  std::string device_driver;  ///< SourceInfo::driver of the opened device
};

/// The device of `kind` (hid, or psvr2 when built with the libusb driver).
Result<LiveDevice> live_device(const std::string& kind);

/// Replays the device's pattern through the pipeline foveald runs (default profile,
/// Vive Pro Eye) and compares every trace row from the first one with an eye in view:
/// each must be the pipeline's output for one of the next reports (nearest first to
/// the spacing of the row times).
struct FollowResult {
  std::size_t rows = 0, matched = 0, first_row = 0;
  std::uint64_t k0 = 0;
  std::size_t resyncs = 0;      ///< rows found only by the wide search ...
  std::int64_t max_resync = 0;  ///< ... at most this many reports past the estimate
  std::string problem;
};

/// `t0`: the absolute time of the trace's first sample.
FollowResult check_follows(const std::vector<TraceRow>& rows, TimeNs t0, const LiveDevice& dev);

}  // namespace foveal::vmtest
