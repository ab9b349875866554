#pragma once
// Leveled logging to stderr for the command-line programs. The level comes from -v/-q
// or $FOVEAL_LOG (error, warn, info, debug). Thread-safe (one fprintf per message).
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

inline void error(const std::string& m) { write(Level::error, m); }
inline void warn(const std::string& m) { write(Level::warn, m); }
inline void info(const std::string& m) { write(Level::info, m); }
inline void debug(const std::string& m) { write(Level::debug, m); }

}  // namespace foveal::log
