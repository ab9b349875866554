#pragma once
// Splitting delimited rows and parsing numbers without allocation (std::from_chars).
#include <charconv>
#include <cstdint>
#include <string_view>
#include <system_error>
#include <vector>

namespace foveal {

/// Splits `line` at `delim` into `out` (cleared first). No quoting: none of the formats
/// foveal reads quotes numeric fields.
inline void split_fields(std::string_view line, char delim, std::vector<std::string_view>& out) {
  out.clear();
  std::size_t pos = 0;
  for (;;) {
    const std::size_t d = line.find(delim, pos);
    if (d == std::string_view::npos) {
      out.push_back(line.substr(pos));
      return;
    }
    out.push_back(line.substr(pos, d - pos));
    pos = d + 1;
  }
}

/// Parses the whole field as T; false if empty, partial, out of range or not a number.
/// Accepts "nan"/"inf" for floating types: callers decide whether those are allowed.
template <class T>
bool parse_number(std::string_view s, T& out) {
  if (s.empty()) return false;
  const char* b = s.data();
  const char* e = b + s.size();
  if constexpr (std::is_floating_point_v<T>) {
    if (*b == '+') ++b;  // from_chars rejects a leading '+', some writers emit one
  }
  auto [p, ec] = std::from_chars(b, e, out);
  return ec == std::errc() && p == e;
}

}  // namespace foveal
