#pragma once
// The runtime probe's two halves: the OpenXR calls (runtime_probe.cpp), made only in a
// child process, and the child's supervision (probe_process.cpp).
#include "foveal/openxr/status.hpp"

namespace foveal::openxr {

/// Loads the runtime through the loader in this process and asks for its HMD system's
/// eye gaze. Only for the probe's child: a broken runtime may crash or hang here.
RuntimeGaze probe_runtime_here();

/// Runs probe_runtime_here in a child process with its output captured, waiting at most
/// timeout_s for the answer; a crash, a hang or an exit without an answer is reported.
RuntimeGaze probe_runtime_in_child(double timeout_s);

}  // namespace foveal::openxr
