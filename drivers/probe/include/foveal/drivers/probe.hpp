#pragma once
// The one place every program gets every gaze driver (the way Monado's target lists
// give every program every device): a source spec names a source and this module opens
// it. foveald --source, foveal devices and foveal record all go through here, so a new
// driver is its own folder under drivers/ plus one entry in src/driver_list.cpp.
//
// Specs (docs/drivers.md):
//   replay:PATH        a native gaze log
//   synthetic[:SEED]   the seeded scanpath generator, in real time
//   hid[:ID|PATH]      a HUTRR74 eye tracker (an id from `foveal devices` or a hidraw node;
//                      none: the first one found)
//   psvr2              a PlayStation VR2 headset over libusb
//   auto               the first live tracker found (HID first, then PS VR2)
// Thread safety: every function may be called from any thread; the sources they make
// are driven by one thread at a time (GazeSource's rule).
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/display_model.hpp"
#include "foveal/core/gaze_source.hpp"
#include "foveal/core/pose_device.hpp"
#include "foveal/drivers/replay_source.hpp"

namespace foveal::probe {

struct SourceSpec {
  std::string driver;  ///< replay, synthetic, hid, psvr2 or auto
  std::string arg;     ///< what follows the colon ("" if nothing)
  std::string text() const { return arg.empty() ? driver : driver + ":" + arg; }
};

/// Parses a spec. Errors (bad_input): an unknown driver (the message lists the known
/// ones, and says when a driver was left out of this build), a missing or extra argument.
Result<SourceSpec> parse_source_spec(const std::string& text);

/// `foveal record --device`'s older forms as a spec: "" or auto, an id from
/// list_devices(), a hidraw path, psvr2; anything with a colon is taken as a spec.
std::string device_spec(const std::string& device);

/// One line per spec form, for --help texts.
std::string source_spec_help();

/// Settings for the sources that take them.
struct SourceOptions {
  ReplayOptions replay;       ///< speed, loop, window; the path comes from the spec
  double synthetic_speed = 1; ///< 1: real time (as a tracker would), 0: as fast as possible
  double synthetic_duration_s = 0;  ///< 0: endless
  std::function<void(const std::string&)> log;  ///< drivers' problem lines; default stderr
};

/// A source made from a spec, not opened yet.
struct OpenedSource {
  std::unique_ptr<GazeSource> source;
  SourceSpec spec;
  bool live = false;  ///< a device: callers wait for it and ride out unplugs
  /// The driver's counters as JSON. Reads driver state: call it on the thread that
  /// drives the source (or after it stopped).
  std::function<nlohmann::json()> counters;
};

/// Makes the source a spec names. Errors: bad_input for a spec naming no such tracker
/// id, or a bad replay/synthetic setting; io_error when device enumeration fails.
Result<OpenedSource> make_source(const SourceSpec& spec, const SourceOptions& options = {});

/// A tracker present on this machine.
struct DeviceRow {
  std::size_t id = 0;
  std::string driver;  ///< the spec's driver: hid or psvr2
  std::string spec;    ///< the spec that opens exactly this device
  std::string path, vid_pid, name, serial, problem;
  double rate_hz = 0;  ///< 0: unknown
};

/// Every live tracker present, in the order `auto` tries them. With `probe_rate`, HID
/// trackers are opened briefly to read their rate (a device that cannot be opened is
/// still listed, with the problem). Errors: io_error when enumeration itself fails.
Result<std::vector<DeviceRow>> list_devices(bool probe_rate);

nlohmann::json device_json(const DeviceRow& row);

// ---- Head pose: the headsets' own tracking (docs/headset.md) ----
// Specs (foveald --head, foveal record --head):
//   psvr2        a PlayStation VR2's SLAM poses (6DoF) and IMU (for prediction)
//   vive[:PATH]  an HTC Vive / Vive Pro's IMU (3DoF, fused), and its lens data
//   auto         the first headset found (PS VR2, then Vive), chosen again at each open
// (foveald also takes recorded and static, which need no device.)

struct PoseSpec {
  std::string driver;  ///< psvr2, vive or auto
  std::string arg;
  std::string text() const { return arg.empty() ? driver : driver + ":" + arg; }
};

/// Parses a head-pose device spec. Errors (bad_input) list the known forms.
Result<PoseSpec> parse_pose_spec(const std::string& text);
/// One line per form, for --help texts.
std::string pose_spec_help();

/// The headset's own display model as its driver read it (after open()), with a line
/// for the model file's "source" key.
struct HeadsetDisplay {
  DisplayModel model;
  std::string source;
};

struct OpenedPoseDevice {
  std::unique_ptr<PoseDevice> device;
  PoseSpec spec;
  /// The driver's counters as JSON (call on the thread driving the device, or after).
  std::function<nlohmann::json()> counters;
  /// The display model read from the headset at the last open(), if its driver reads
  /// one (Vive); nullopt otherwise. Same thread rule as counters.
  std::function<std::optional<HeadsetDisplay>()> display;
};

/// Makes the pose device a spec names, not opened yet.
Result<OpenedPoseDevice> make_pose_device(const PoseSpec& spec, const SourceOptions& options = {});

/// A headset present and what it provides.
struct HmdRow {
  std::size_t id = 0;
  std::string driver;     ///< psvr2, vive
  std::string pose_spec;  ///< the --head spec for its pose
  std::string gaze_spec;  ///< the --source spec for its gaze ("" if foveal reads none from it)
  std::string path, vid_pid, name, serial;
  std::vector<std::string> provides;  ///< e.g. "gaze", "6dof pose", "imu 2000 Hz", "display model"
  std::string problem;
};

/// A Vive configuration JSON (as the headset stores it; `where` names it in errors)
/// converted to a display model, without a device. Errors: bad_input naming the key,
/// or a build without the Vive driver.
Result<HeadsetDisplay> display_from_vive_config(const std::string& json, const std::string& where);

/// Every headset with a pose present, in the order `auto` tries them. Errors: io_error
/// when enumeration itself fails.
Result<std::vector<HmdRow>> list_hmds();
nlohmann::json hmd_json(const HmdRow& row);

}  // namespace foveal::probe
