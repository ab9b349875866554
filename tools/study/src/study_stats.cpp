#include "foveal/study/study_stats.hpp"

#include <algorithm>
#include <cmath>

#include "foveal/study/binomial_test.hpp"

namespace foveal {

namespace {

template <class T, class Match>
T& find_or_add(std::vector<T>& items, Match match, T fresh) {
  for (T& item : items)
    if (match(item)) return item;
  items.push_back(std::move(fresh));
  return items.back();
}

}  // namespace

StudyStats compute_study_stats(const StudyTrials& trials, double score_threshold) {
  StudyStats st;
  st.validation_trials = trials.validation_trials;
  for (const ChoiceTrial& t : trials.choices) {
    const std::string& chosen = t.chose_a ? t.condition_a : t.condition_b;
    PairVotes& p = find_or_add(
        st.pairs,
        [&](const PairVotes& q) {
          return (q.first == t.condition_a && q.second == t.condition_b) ||
                 (q.first == t.condition_b && q.second == t.condition_a);
        },
        PairVotes{t.condition_a, t.condition_b});
    ++p.trials;
    ++(chosen == p.first ? p.votes_first : p.votes_second);
  }
  for (PairVotes& p : st.pairs) {
    p.share_first = static_cast<double>(p.votes_first) / static_cast<double>(p.trials);
    p.p_value = binomial_test_two_sided(p.votes_first, p.trials, 0.5);
  }

  // Scores are small integers: their sums and sums of squares are exact in a double.
  std::vector<double> sum_sq;
  for (const ScoreTrial& t : trials.scores) {
    ConditionScore& c = find_or_add(
        st.scores, [&](const ConditionScore& q) { return q.condition == t.condition; }, ConditionScore{t.condition});
    sum_sq.resize(st.scores.size());
    ++c.trials;
    c.mean += t.score;
    sum_sq[static_cast<std::size_t>(&c - st.scores.data())] += t.score * t.score;
  }
  for (std::size_t i = 0; i < st.scores.size(); ++i) {
    ConditionScore& c = st.scores[i];
    const auto n = static_cast<double>(c.trials);
    const double sum = c.mean;
    c.mean = sum / n;
    if (c.trials > 1) c.sd = std::sqrt(std::max(0.0, (sum_sq[i] - sum * sum / n) / (n - 1)));
  }
  st.sigmas = estimate_sigmas(trials.scores, score_threshold);
  return st;
}

}  // namespace foveal
