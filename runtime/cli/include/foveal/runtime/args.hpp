#pragma once
// Parsers for the compound command-line values shared by foveal and foveald.
#include <string>
#include <utility>

#include "foveal/core/error.hpp"

namespace foveal::cli {

/// "X,Y" -> two finite numbers. `what` names the option in the message.
Result<std::pair<double, double>> parse_point(const std::string& s, const std::string& what);
/// "WxH" -> two positive integers.
Result<std::pair<int, int>> parse_size(const std::string& s, const std::string& what);

}  // namespace foveal::cli
