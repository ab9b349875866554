#pragma once
// Splitting delimited rows and parsing numbers without allocation (std::from_chars).
#include <bit>
#include <charconv>
#include <cmath>
#include <cstring>
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

namespace detail {

/// Accumulates the digit run at p (not past e) into m; returns the end of the run.
inline const char* read_digits(const char* p, const char* e, std::uint64_t& m, int& count) {
  while (p != e && static_cast<unsigned>(*p - '0') < 10) {
    m = m * 10 + static_cast<unsigned>(*p++ - '0');
    ++count;
  }
  return p;
}

/// The value of the 8 ASCII digits in `v` (first digit in the lowest byte): pairs,
/// then quads, then all eight, with three multiplies.
inline std::uint32_t digits8_value(std::uint64_t v) {
  v -= 0x3030303030303030ull;
  v = v * 10 + (v >> 8);
  v = (v & 0x00FF00FF00FF00FFull) * 100 + ((v >> 16) & 0x00FF00FF00FF00FFull);
  v = (v & 0x0000FFFF0000FFFFull) * 10000 + ((v >> 32) & 0x0000FFFFull);
  return static_cast<std::uint32_t>(v);
}

/// Like read_digits, but takes up to 8 digits with one load and no per-digit branch
/// (a data-dependent loop exit costs a branch miss per field). Needs 8 readable bytes
/// at p even when e - p < 8: LineReader guarantees that for the lines it returns.
inline const char* read_digits_padded(const char* p, const char* e, std::uint64_t& m, int& count) {
  static constexpr std::uint64_t kScale[] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000};
  std::uint64_t v;
  std::memcpy(&v, p, 8);
  // High bit of each non-digit byte; bytes after the first non-digit may be wrong
  // (borrows and carries run upwards only), and only the first one matters.
  const std::uint64_t t = v - 0x3030303030303030ull;
  const std::uint64_t non_digit = ((t + 0x7676767676767676ull) | t) & 0x8080808080808080ull;
  std::ptrdiff_t n = non_digit ? std::countr_zero(non_digit) >> 3 : 8;
  if (n > e - p) n = e - p;
  if (n <= 0) return p;
  // Keep the n digits and put '0's in front of them: same value, eight digits.
  const auto shift = static_cast<unsigned>(8 * (8 - n));
  const std::uint64_t zeros = shift ? 0x3030303030303030ull >> (64 - shift) : 0;
  m = m * kScale[n] + digits8_value((v << shift) | zeros);
  count += static_cast<int>(n);
  p += n;
  return n == 8 ? read_digits(p, e, m, count) : p;
}

/// Fast path for plain decimal floats ("-0.1235", "3.5e-7") at the start of [b, e):
/// digits into an integer mantissa m < 2^53, scaled by one correctly rounded double
/// multiply or divide by an exact power of ten (<= 1e22), then rounded to float unless
/// the double lies within 2^-50 (relative) of a midpoint between two floats, where
/// rounding twice could differ from rounding once. Returns the end of the number, or nullptr
/// when it cannot decide (the caller then uses std::from_chars), so the results always
/// equal std::from_chars. kPadded: see read_digits_padded.
template <bool kPadded = false>
inline const char* parse_float_prefix(const char* b, const char* e, float& out) {
  static constexpr double kPow10[] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                      1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
  const char* p = b;
  const bool neg = p != e && *p == '-';
  p += neg;  // no branch: signs of gaze components are as good as random
  std::uint64_t m = 0;
  int digits = 0, exp10 = 0;
  const char* start = p;
  p = read_digits(p, e, m, digits);  // integer parts are short: a plain loop is cheapest
  const int int_digits = digits;
  if (p != e && *p == '.') {
    if constexpr (kPadded) p = read_digits_padded(p + 1, e, m, digits);
    else p = read_digits(p + 1, e, m, digits);
    exp10 = int_digits - digits;
  }
  if (p == start || digits == 0 || digits > 15) return nullptr;
  if (p != e && (*p == 'e' || *p == 'E')) {
    ++p;
    bool eneg = false;
    if (p != e && (*p == '-' || *p == '+')) eneg = *p++ == '-';
    int x = 0, xd = 0;
    while (p != e && static_cast<unsigned>(*p - '0') < 10 && xd < 4) {
      x = x * 10 + (*p++ - '0');
      ++xd;
    }
    if (xd == 0) return nullptr;
    exp10 += eneg ? -x : x;
  }
  if (exp10 < -22 || exp10 > 22) return nullptr;
  if (m < (1u << 24) && exp10 <= 0 && exp10 >= -10) {
    // Clinger's fast path in float itself: m and 10^k (k <= 10) are exact floats and one
    // IEEE division rounds correctly. Covers the 7-digit values trackers write.
    static constexpr float kPow10f[] = {1e0f, 1e1f, 1e2f, 1e3f, 1e4f, 1e5f, 1e6f, 1e7f, 1e8f, 1e9f, 1e10f};
    const float f = static_cast<float>(m) / kPow10f[-exp10];
    out = neg ? -f : f;
    return p;
  }
  const double d = exp10 < 0 ? static_cast<double>(m) / kPow10[-exp10] : static_cast<double>(m) * kPow10[exp10];
  const float f = static_cast<float>(d);
  if (d == 0.0) {
    out = neg ? -0.0f : 0.0f;
    return p;
  }
  if (!std::isfinite(f)) return nullptr;
  // d > 0: the neighbour float on d's side is one step up or down in the bit pattern.
  const std::uint32_t bits = std::bit_cast<std::uint32_t>(f);
  const float g = std::bit_cast<float>(d > static_cast<double>(f) ? bits + 1 : bits - 1);
  const double mid = 0.5 * (static_cast<double>(f) + static_cast<double>(g));
  if (std::fabs(d - mid) <= d * 0x1p-50) return nullptr;
  out = neg ? -f : f;
  return p;
}

}  // namespace detail

/// Parses the whole field as T; false if empty, partial, out of range or not a number.
/// Accepts "nan"/"inf" for floating types: callers decide whether those are allowed.
template <class T>
bool parse_number(std::string_view s, T& out) {
  if (s.empty()) return false;
  const char* b = s.data();
  const char* e = b + s.size();
  if constexpr (std::is_floating_point_v<T>) {
    if (*b == '+' && ++b != e && *b == '-') return false;  // from_chars rejects '+'; some writers emit it
    if constexpr (std::is_same_v<T, float>)
      if (detail::parse_float_prefix(b, e, out) == e) return true;
  }
  auto [p, ec] = std::from_chars(b, e, out);
  return ec == std::errc() && p == e;
}

/// Why parse_number<T> refused `s`, for messages: "out of range" when it is a well-formed
/// number that T cannot hold ("1e308" as a float, 2^64 as an int64), else `otherwise`
/// ("not a number", "not an integer").
template <class T>
const char* number_problem(std::string_view s, const char* otherwise = "not a number") {
  const char* b = s.data();
  const char* e = b + s.size();
  if (b != e && *b == '+') ++b;
  T v{};
  auto [p, ec] = std::from_chars(b, e, v);
  return b != e && ec == std::errc::result_out_of_range && p == e ? "out of range" : otherwise;
}

}  // namespace foveal
