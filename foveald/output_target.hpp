#pragma once
// foveald's outputs are checked before any work: a target that AtomicFile would refuse at
// the end (a symbolic link, FIFO, device, directory) ends the session before it starts,
// with its name, rather than after minutes of rendering without a summary.
#include <string>

#include "foveal/core/error.hpp"

namespace foveal::daemon {

/// bad_input naming `path` unless it is absent or a regular file (AtomicFile's rule,
/// with its words).
Status check_output_target(const std::string& path);

}  // namespace foveal::daemon
