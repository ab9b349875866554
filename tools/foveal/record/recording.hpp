#pragma once
// What `foveal record` does once its options are parsed: reads a gaze source into a native
// gaze log, riding out unplugs (retry with backoff) until the duration is over or Ctrl-C;
// with a control socket, `mark` requests become marker rows; with a head spec, the
// headset's pose goes with each sample (log v2, docs/headset.md); at the end the
// recording's data quality (docs/quality.md).
#include <string>

#include "foveal/core/error.hpp"
#include "foveal/drivers/probe.hpp"

namespace foveal::cmd {

struct RecordRequest {
  std::string out;      ///< --out: the native gaze log, written atomically
  std::string targets;  ///< --targets: a targets CSV for the end report's accuracy; empty: none
  std::string head;     ///< --head: a pose spec; empty: gaze only
  std::string control_socket;  ///< --control-socket
  double duration_s = 10;      ///< > 0
  bool control = false;        ///< --control: serve the control socket (default path unless control_socket)
  bool json = false;           ///< print the summary as JSON
};

/// Opens the source `spec` names, records until the duration ends, the source ends or
/// SIGINT/SIGTERM, commits the log and prints the summary with its quality. Errors name
/// the device, file or socket; the log is not written on an error.
Status record_gaze(const probe::SourceSpec& spec, const RecordRequest& r);

}  // namespace foveal::cmd
