#pragma once
// The memory bound of commands whose working set grows with their input (metrics --jod,
// render --size): the need is estimated from headers and options before any work and
// refused past the bound with exit 2, rather than found by bad_alloc half way
// (docs/bad-input.md, "Round 3").
#include <cstdint>
#include <string>

#include "foveal/core/error.hpp"

namespace foveal::evaluation {

/// The variable that sets the bound, in GB (10^9 bytes).
inline constexpr const char* kMemoryLimitVariable = "FOVEAL_MEMORY_LIMIT_GB";

/// The bound in bytes: FOVEAL_MEMORY_LIMIT_GB if set (a number in (0, 1e6]), else 8 GB or
/// half the machine's memory if that is less. bad_input for a malformed variable.
Result<std::uint64_t> memory_bound_bytes();

/// bad_input "needs about X GB for WHAT; the bound is N GB (FOVEAL_MEMORY_LIMIT_GB=G
/// raises it)" when `need_bytes` exceeds the bound.
Status check_memory(std::uint64_t need_bytes, const std::string& what);

/// "10.2 GB", "850 MB": sizes in these messages (decimal units, as the variable's).
std::string shown_gb(std::uint64_t bytes);

}  // namespace foveal::evaluation
