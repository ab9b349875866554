#pragma once
// The layer's log: one line at a time to the app's stderr, never blocking. An app's
// stderr may be a pipe nobody reads (launchers do that): the layer writes through a
// file description of its own opened with O_NONBLOCK (the app's keeps its flags), a
// line that does not fit is dropped and counted, and SIGPIPE from a reader that is gone
// never reaches the app. Any thread.
#include <cstdint>

namespace foveal::openxr {

void log_line(const char* text);
/// Lines dropped because stderr could not take them at once.
std::uint64_t log_lines_dropped();

}  // namespace foveal::openxr
