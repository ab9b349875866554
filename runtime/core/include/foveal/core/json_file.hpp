#pragma once
// Reading a JSON document from a file, with errors that name the file.
#include <string>

#include <nlohmann/json.hpp>

#include "foveal/core/error.hpp"

namespace foveal {

/// `what` names the kind of file in the "cannot open" message ("profile", "display model").
Result<nlohmann::json> read_json_file(const std::string& path, const std::string& what);

}  // namespace foveal
