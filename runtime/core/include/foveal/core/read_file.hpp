#pragma once
// Reading a whole input file with a size bound. Only regular files are read: a FIFO
// with no writer would block the caller (and its signal handling) forever, a device
// or a directory is never what the user meant.
#include <cstddef>
#include <string>

#include "foveal/core/error.hpp"

namespace foveal {

/// Opens `path` for reading without blocking and checks it is a regular file.
/// Returns the file descriptor (blocking again, close-on-exec); errors name the path
/// and `what` ("profile", "gaze log").
Result<int> open_regular_file(const std::string& path, const std::string& what);

/// The file's bytes; a file larger than `max_bytes` is refused before anything is read.
Result<std::string> read_regular_file(const std::string& path, std::size_t max_bytes, const std::string& what);

/// "1 MiB", "64 MiB", "1536 bytes": sizes in messages.
std::string describe_bytes(std::size_t bytes);

}  // namespace foveal
