#pragma once
// The data-quality report of docs/quality.md as JSON and as text: `foveal log quality`
// prints it for a log, `foveal record` for the recording it just made.
#include <string>

#include <nlohmann/json.hpp>

#include "foveal/quality/gaze_quality.hpp"

namespace foveal::evaluation {

nlohmann::json quality_json(const std::string& path, const GazeQuality& q);
void print_quality_text(const std::string& path, const GazeQuality& q);

}  // namespace foveal::evaluation
