#include "foveal/study/sigma_estimates.hpp"

#include <algorithm>

namespace foveal {

namespace {

struct Point {
  double sigma, mean;
};

// The first crossing below `threshold` of the curve through `points` (ascending sigma).
SigmaEstimate first_crossing(const std::vector<Point>& points, double threshold) {
  if (points.front().mean < threshold) return {points.front().sigma, EstimateBound::below_range};
  for (std::size_t i = 1; i < points.size(); ++i) {
    const Point& lo = points[i - 1];
    const Point& hi = points[i];
    if (hi.mean < threshold) {
      const double t = (lo.mean - threshold) / (lo.mean - hi.mean);  // lo.mean >= threshold > hi.mean
      return {lo.sigma + t * (hi.sigma - lo.sigma), EstimateBound::interpolated};
    }
  }
  return {points.back().sigma, EstimateBound::at_least};
}

}  // namespace

const char* estimate_bound_name(EstimateBound b) {
  switch (b) {
    case EstimateBound::interpolated: return "interpolated";
    case EstimateBound::at_least: return "at_least";
    case EstimateBound::below_range: return "below_range";
  }
  return "?";
}

namespace {

std::string method_of(const std::string& condition) { return condition.substr(0, condition.find(' ')); }

SigmaEstimates estimate_method(std::span<const ScoreTrial> trials, const std::string& method, double threshold) {
  SigmaEstimates e;
  e.method = method;
  e.threshold = threshold;
  for (const ScoreTrial& t : trials) {
    if (!t.sigma_d || !t.sigma_nd || method_of(t.condition) != method) continue;
    auto it = std::find_if(e.levels.begin(), e.levels.end(),
                           [&](const LevelScore& l) { return l.sigma_d == *t.sigma_d && l.sigma_nd == *t.sigma_nd; });
    if (it == e.levels.end()) it = e.levels.insert(e.levels.end(), LevelScore{*t.sigma_d, *t.sigma_nd});
    ++it->trials;
    it->mean += t.score;
  }
  for (LevelScore& l : e.levels) l.mean /= static_cast<double>(l.trials);
  std::sort(e.levels.begin(), e.levels.end(), [](const LevelScore& a, const LevelScore& b) {
    return a.sigma_d != b.sigma_d ? a.sigma_d < b.sigma_d : a.sigma_nd < b.sigma_nd;
  });

  std::vector<Point> uniform;
  for (const LevelScore& l : e.levels)
    if (l.sigma_d == l.sigma_nd) uniform.push_back({l.sigma_d, l.mean});
  if (uniform.empty()) return e;
  e.sigma_uf = first_crossing(uniform, threshold);

  // The non-dominant series: sigma_d fixed near sigma_UF, sigma_nd rising.
  std::optional<double> base;
  for (const LevelScore& l : e.levels)
    if (l.sigma_nd > l.sigma_d && l.sigma_d <= e.sigma_uf->sigma) base = l.sigma_d;  // ascending: the largest
  if (!base)
    for (const LevelScore& l : e.levels)
      if (l.sigma_nd > l.sigma_d) {
        base = l.sigma_d;
        break;
      }
  if (!base) return e;
  std::vector<Point> nd;
  for (const LevelScore& l : e.levels)
    if (l.sigma_d == *base) nd.push_back({l.sigma_nd, l.mean});  // includes the uniform level when tested
  e.sigma_nf = first_crossing(nd, threshold);
  e.sigma_nf_at_sigma_d = *base;
  return e;
}

}  // namespace

std::vector<SigmaEstimates> estimate_sigmas(std::span<const ScoreTrial> trials, double threshold) {
  std::vector<SigmaEstimates> out;
  for (const ScoreTrial& t : trials) {
    if (!t.sigma_d || !t.sigma_nd) continue;
    const std::string m = method_of(t.condition);
    if (std::none_of(out.begin(), out.end(), [&](const SigmaEstimates& e) { return e.method == m; }))
      out.push_back(estimate_method(trials, m, threshold));
  }
  return out;
}

}  // namespace foveal
