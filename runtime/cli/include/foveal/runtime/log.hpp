#pragma once
// Leveled logging to stderr for the command-line programs. The level comes from -v/-q
// or $FOVEAL_LOG (error, warn, info, debug). Thread-safe (whole lines from each thread).
//
// By default a line is written at once. A daemon calls start_writer_thread(): lines then
// go through a bounded queue to a thread of their own, and stdout and stderr become the
// program's own non-blocking descriptions of what they were (a pipe, a FIFO, a terminal),
// so that a reader that does not read (a full pipe, a stopped terminal) never blocks any
// thread, a library's direct writes and the exit-time flush included; lines that find the
// queue full or the reader gone are dropped and counted (dropped_lines()).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace foveal::log {

enum class Level { error = 0, warn = 1, info = 2, debug = 3 };

/// Sets the program name shown and the level: $FOVEAL_LOG (default info), shifted by
/// `verbosity` (+1 per -v, -1 per -q).
void init(const char* program, int verbosity);
Level level();
bool enabled(Level l);
void write(Level l, const std::string& msg);
/// Text as it is (a status line with its own "\r"), through the same path as lines.
void raw(const std::string& text);

inline void error(const std::string& m) { write(Level::error, m); }
inline void warn(const std::string& m) { write(Level::warn, m); }
inline void info(const std::string& m) { write(Level::info, m); }
inline void debug(const std::string& m) { write(Level::debug, m); }

/// Bytes of text the queue holds before it drops lines.
inline constexpr std::size_t kMaxQueuedBytes = 256 * 1024;
/// From here on lines are queued and written by a thread (all signals blocked in it),
/// which waits for room in poll(), never in write(); stdout and stderr no longer block
/// (above; a socket is written with MSG_DONTWAIT, a pipe that cannot be reopened only
/// as far as poll() says it fits). Call once, early; there is no way back.
void start_writer_thread();
/// Lines dropped because the queue was full or stderr's reader was gone (0 without the
/// writer thread).
std::uint64_t dropped_lines();
/// Waits until the queue is written out; false when the writer made no progress for
/// `stall_ms` (stderr stuck) or took twice that in all, so that an exit is never held up
/// by a silent reader.
bool flush(int stall_ms);
/// Writes `text` to stdout (a summary, JSON), waiting for room as flush() does; false
/// when not all of it went. Without the writer thread: stdio, as it is.
bool out(const std::string& text, int stall_ms);

}  // namespace foveal::log
