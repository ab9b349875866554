#pragma once
// foveald's own messages and its stdout go through the log's sink (foveal/runtime/log.hpp):
// no write of foveald's may wait for a reader that does not read, or SIGTERM could not
// end it (docs/daemon.md, "Signals").
#include <string>

#include <nlohmann/json.hpp>

#include "foveal/core/json_text.hpp"
#include "foveal/core/error.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/runtime/log.hpp"

namespace foveal::daemon {

/// How long foveald's last words may wait for a stdout or stderr that takes nothing:
/// together well inside the 1 s SIGTERM is promised.
inline constexpr int kOutputStallMs = 150;

/// The error as "foveald: error: ...", queued like every line; its exit code.
inline int report(const Error& e) {
  log::error(e.message);
  return e.kind == ErrorKind::internal ? cli::kExitFailure : cli::kExitBadInput;
}

inline void print_json(const nlohmann::json& j) { (void)log::out(json_text(j, 2) + "\n", kOutputStallMs); }

}  // namespace foveal::daemon
