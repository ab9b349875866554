#pragma once
// The exact binomial test (docs/study.md).
#include <cstdint>

namespace foveal {

/// Two-sided p-value of k successes in n trials under success probability p (0 < p < 1):
/// the total probability of every outcome no more likely than k, the definition SciPy's
/// binomtest uses (with its relative tolerance of 1e-7 when comparing likelihoods).
/// Requires k <= n.
double binomial_test_two_sided(std::uint64_t k, std::uint64_t n, double p = 0.5);

}  // namespace foveal
