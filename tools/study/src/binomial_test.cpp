#include "foveal/study/binomial_test.hpp"

#include <algorithm>
#include <cmath>

namespace foveal {

namespace {

double log_pmf(std::uint64_t i, std::uint64_t n, double p) {
  const auto x = static_cast<double>(i), m = static_cast<double>(n);
  return std::lgamma(m + 1) - std::lgamma(x + 1) - std::lgamma(m - x + 1) + x * std::log(p) +
         (m - x) * std::log1p(-p);
}

}  // namespace

double binomial_test_two_sided(std::uint64_t k, std::uint64_t n, double p) {
  if (n == 0) return 1.0;
  // Outcomes count when their likelihood is at most the observed one's, within a
  // relative 1e-7 so that ties computed with rounding errors still count as ties.
  const double threshold = log_pmf(k, n, p) + std::log1p(1e-7);
  // The pmf rises to the mode and falls after it, so the outcomes that count are the two
  // tails; sum each from its end inwards (small terms first) until a term is too likely.
  double sum = 0;
  std::uint64_t low = 0;  // outcomes [0, low) are summed
  for (; low <= n; ++low) {
    const double lp = log_pmf(low, n, p);
    if (lp > threshold) break;
    sum += std::exp(lp);
  }
  for (std::uint64_t i = n; i > low; --i) {  // pmf(low) is too likely, if low <= n
    const double lp = log_pmf(i, n, p);
    if (lp > threshold) break;
    sum += std::exp(lp);
  }
  return std::min(1.0, sum);
}

}  // namespace foveal
