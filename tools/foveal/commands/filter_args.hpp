#pragma once
// The filter and display options that `replay` and `predict-eval` share: --config FILE
// or --profile NAME chooses the gaze pipeline's settings, --display FILE the display
// model (default: the Vive Pro Eye's).
#include <string>

#include "foveal/core/display_model.hpp"
#include "foveal/core/error.hpp"
#include "foveal/runtime/filter_config.hpp"

namespace foveal::cmd {

/// The filter settings from a JSON file or a stored profile, or the defaults with
/// neither. Errors: both given (naming `command`), an unreadable or invalid file, an
/// unknown profile.
Result<FilterConfig> filter_config_from(const std::string& config, const std::string& profile, const char* command);

/// The display model at `path`, or the Vive Pro Eye's for an empty path.
Result<DisplayModel> display_model_from(const std::string& path);

}  // namespace foveal::cmd
