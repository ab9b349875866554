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
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/core/gaze_source.hpp"
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

}  // namespace foveal::probe
