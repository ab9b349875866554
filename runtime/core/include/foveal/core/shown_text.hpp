#pragma once
// A piece of the input quoted in an error message: at most kMaxShownBytes bytes, then
// "…", control bytes as \xNN. A message never carries an unbounded (or binary) value.
#include <cstddef>
#include <cstdio>
#include <string>
#include <string_view>

namespace foveal {

inline constexpr std::size_t kMaxShownBytes = 60;

/// `text` for a message, cut at `max` bytes (never inside a UTF-8 sequence) + "…".
inline std::string shown_text(std::string_view text, std::size_t max = kMaxShownBytes) {
  std::size_t n = text.size();
  if (n > max) {
    n = max;
    while (n > 0 && (static_cast<unsigned char>(text[n]) & 0xC0) == 0x80) --n;  // a continuation byte
  }
  std::string out;
  out.reserve(n + 4);
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c < 0x20 || c == 0x7f) {
      char esc[5];
      std::snprintf(esc, sizeof esc, "\\x%02x", c);
      out += esc;
    } else {
      out += static_cast<char>(c);
    }
  }
  if (n < text.size()) out += "…";
  return out;
}

/// A number for a message as a person writes it: 2, 2.8, 0.001, 1e+30 (at most six
/// significant digits), never 2.000000.
inline std::string shown_number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", v);
  return b;
}

}  // namespace foveal
