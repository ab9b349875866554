#include "foveal/evaluation/memory_bound.hpp"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace foveal::evaluation {

namespace {

constexpr double kGB = 1e9;
constexpr std::uint64_t kDefaultBound = 8'000'000'000;

std::string shown_limit(double gb) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", gb);
  return buf;
}

}  // namespace

std::string shown_gb(std::uint64_t bytes) {
  char buf[32];
  if (bytes >= 1'000'000'000) std::snprintf(buf, sizeof buf, "%.1f GB", static_cast<double>(bytes) / kGB);
  else std::snprintf(buf, sizeof buf, "%.0f MB", std::ceil(static_cast<double>(bytes) / 1e6));
  return buf;
}

Result<std::uint64_t> memory_bound_bytes() {
  if (const char* v = std::getenv(kMemoryLimitVariable); v && *v) {
    char* end = nullptr;
    errno = 0;
    const double gb = std::strtod(v, &end);
    if (*end != '\0' || errno == ERANGE || !(gb > 0 && gb <= 1e6))
      return bad_input(std::string(kMemoryLimitVariable) + ": '" + std::string(v).substr(0, 40) +
                       "' is not a number of GB in (0, 1000000]");
    return static_cast<std::uint64_t>(gb * kGB);
  }
  // Half the machine's memory at most: the rest is the system's and other programs'.
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGESIZE);
  if (pages > 0 && page > 0)
    return std::min(kDefaultBound, static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page) / 2);
  return kDefaultBound;
}

Status check_memory(std::uint64_t need_bytes, const std::string& what) {
  auto bound = memory_bound_bytes();
  if (!bound) return bound.error();
  if (need_bytes <= *bound) return {};
  // The smallest whole number of GB that would do, for the message.
  const double raise = std::ceil(static_cast<double>(need_bytes) / kGB * 1.1);
  return bad_input("needs about " + shown_gb(need_bytes) + " for " + what + "; the bound is " + shown_gb(*bound) + " (" +
                   kMemoryLimitVariable + "=" + shown_limit(raise) + " raises it)");
}

}  // namespace foveal::evaluation
