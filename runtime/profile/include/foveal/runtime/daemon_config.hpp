#pragma once
// foveald's options file, <config>/foveal/foveald.conf (<config>: $XDG_CONFIG_HOME or
// ~/.config): what the user service runs with (docs/daemon.md, "Service").
//
//   # comments and blank lines are ignored
//   source = auto
//   quality = jod:9.5
//
// One `key = value` per line; each key at most once; the keys are foveald's long
// options that make sense for a service (kDaemonConfigKeys), values as on the command
// line. A value foveald cannot use is refused there, at start, naming the file and key.
// Thread safety: plain values and pure functions.
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "foveal/core/error.hpp"

namespace foveal {

struct DaemonConfigKey {
  const char* name;  ///< the key, and foveald's option --name
  const char* help;  ///< one line for `foveal service keys`
};

/// Every key the file may hold.
std::span<const DaemonConfigKey> daemon_config_keys();

class DaemonConfig {
 public:
  /// Parses the file's text; errors name `where:line` and the key or text at fault.
  static Result<DaemonConfig> parse(std::string_view text, const std::string& where);
  /// The file at `path`; a file that is not there is an empty config, a directory, FIFO
  /// or unreadable file an error naming it.
  static Result<DaemonConfig> load(const std::string& path);

  /// The value of `key`, or null.
  const std::string* get(const std::string& key) const;
  /// Sets (or replaces) `key`; an unknown key or a value with a line break is refused.
  Status set(const std::string& key, const std::string& value);
  /// Removes `key`; false when it was not there.
  bool unset(const std::string& key);
  const std::vector<std::pair<std::string, std::string>>& entries() const { return entries_; }
  /// The file's text: one `key = value` line per entry, in the order they were set.
  std::string text() const;

 private:
  std::vector<std::pair<std::string, std::string>> entries_;
};

/// <root>/foveald.conf for a ProfileStore root (<config>/foveal).
std::string daemon_config_path(const std::string& config_root);

}  // namespace foveal
