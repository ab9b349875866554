#pragma once
// The temporary files behind AtomicFile: their names, how a live one is told from one
// a killed writer left, and the registry the signal handler cleans up from.
#include <string>

namespace foveal::atomic_temps {

/// "PATH.tmp." followed by this many letters or digits.
constexpr int kSuffixLength = 6;

/// Creates `target.tmp.XXXXXX` (O_EXCL, never following a link) with `mode` (the umask
/// applies) and takes an exclusive flock on it, which marks it as in use until the
/// descriptor is closed, however the process ends. Returns the fd, or -1 with errno.
int create_locked(const std::string& target, unsigned mode, std::string& tmp_path);

/// Removes temporary files of `target` that nobody holds a lock on, that belong to this
/// user and that are older than a few seconds (the age covers the instant between
/// creating and locking). Best effort: anything it cannot check is left alone.
void remove_stale(const std::string& target);

/// Remembers a temporary name for the signal handler; -1 when every slot is taken.
int register_for_signals(const std::string& tmp_path);
void unregister_for_signals(int slot);

}  // namespace foveal::atomic_temps
