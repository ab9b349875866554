#pragma once
// Runs another program with an argument vector, never through a shell: an argument
// (an output folder, a file name) reaches the program as one argv entry whatever
// characters it holds, so no quoting can turn it into a command (docs/bad-input.md).
#include <string>
#include <vector>

#include "foveal/core/error.hpp"

namespace foveal::cli {

struct ProgramRun {
  int exit_code = -1;  ///< the program's exit status, -1 when a signal ended it
  int signal = 0;      ///< the signal that ended it, else 0
  std::string out;     ///< its stdout when captured
  std::string err;     ///< its stderr when captured
  bool ok() const { return exit_code == 0; }
};

struct Capture {
  bool out = false, err = false;  ///< capture stdout / stderr; otherwise inherited
};

/// Starts argv[0] (a path: PATH is not searched) with `argv`, waits for it and returns
/// how it ended, with stdout and stderr captured as `capture` says (else inherited).
/// An io_error when it cannot be started.
Result<ProgramRun> run_program(const std::vector<std::string>& argv, Capture capture = {});

/// "exit status 3" / "killed by signal 9 (Killed)", for messages.
std::string describe_end(const ProgramRun& r);

}  // namespace foveal::cli
