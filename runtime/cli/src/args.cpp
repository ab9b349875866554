#include "foveal/runtime/args.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace foveal::cli {

namespace {
bool parse_double(const std::string& s, double& out) {
  if (s.empty()) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtod(s.c_str(), &end);
  return *end == '\0' && errno == 0 && std::isfinite(out);
}
}  // namespace

Result<std::pair<double, double>> parse_point(const std::string& s, const std::string& what) {
  const auto comma = s.find(',');
  double x = 0, y = 0;
  if (comma == std::string::npos || !parse_double(s.substr(0, comma), x) || !parse_double(s.substr(comma + 1), y))
    return bad_input(what + ": expected X,Y (two finite numbers), got '" + s + "'");
  return std::make_pair(x, y);
}

Result<std::pair<int, int>> parse_size(const std::string& s, const std::string& what) {
  const auto x = s.find('x');
  double w = 0, h = 0;
  if (x == std::string::npos || !parse_double(s.substr(0, x), w) || !parse_double(s.substr(x + 1), h) || w < 1 || h < 1 ||
      w != std::floor(w) || h != std::floor(h) || w > 65536 || h > 65536)
    return bad_input(what + ": expected WIDTHxHEIGHT (positive integers), got '" + s + "'");
  return std::make_pair(static_cast<int>(w), static_cast<int>(h));
}

}  // namespace foveal::cli
