#pragma once
// foveald as the user service: the options file (foveal/runtime/daemon_config.hpp) turned
// into command-line arguments, so that its values meet the command line's own checks,
// and the service's defaults (wait for the tracker and the headset, no rendering).
#include <functional>
#include <string>
#include <vector>

#include "foveal/core/error.hpp"
#include "options.hpp"

namespace foveal::daemon {

/// $XDG_CONFIG_HOME/foveal/foveald.conf (or ~/.config/...).
std::string default_config_path();

/// $XDG_STATE_HOME/foveal (or ~/.local/state/foveal): the service's outputs (systemd's %S).
std::string default_service_out();

/// The arguments that the file at `path` stands for, for every key whose option the
/// command line did not give (`given("--key")`), then, with `service`, `--source auto`,
/// `--head auto`, `--no-render` and `--out default_service_out()` for what neither gave. A file that is not there
/// stands for nothing; a broken one is an error naming it, the line and the key.
Result<std::vector<std::string>> service_arguments(const std::string& path, bool service,
                                                   const std::function<bool(const std::string&)>& given);

/// The file's keys as `o` has them, in the file's format (`--print-config`).
std::string config_text(const Options& o);

}  // namespace foveal::daemon
