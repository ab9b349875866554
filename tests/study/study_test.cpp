// Study statistics: the exact binomial test against SciPy's binomtest, the trials CSV
// and its errors, and `foveal study stats` end to end.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/study/binomial_test.hpp"
#include "foveal/study/sigma_estimates.hpp"
#include "foveal/study/study_session.hpp"
#include "foveal/study/study_stats.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

using Votes = std::pair<std::uint64_t, std::uint64_t>;  // (votes for the first, trials)

const std::vector<Votes> kVoteCounts = {{38, 48}, {12, 48}, {0, 10}, {10, 10}, {5, 10},    {3, 10},
                                        {7, 13},  {1, 1},   {0, 1},  {26, 50}, {16, 30},   {0, 200},
                                        {137, 250}, {480, 1000}, {100, 1000}, {500, 1000}, {20, 21}};

/// SciPy's two-sided p-values for `votes`, from the system python3 with python3-scipy.
std::vector<double> scipy_p_values(const std::vector<Votes>& votes) {
  std::string cmd = std::string(FOVEAL_SYSTEM_PYTHON3) + " " + test::source_path("tests/study/binomtest_reference.py");
  for (const auto& [k, n] : votes) cmd += " " + std::to_string(k) + "/" + std::to_string(n);
  const auto r = test::run(cmd);
  EXPECT_EQ(r.exit_code, 0) << "the SciPy reference failed (python3-scipy installed? scripts/bootstrap.sh):\n" << r.err;
  if (r.exit_code != 0) return {};
  return nlohmann::json::parse(r.out).get<std::vector<double>>();
}

TEST(BinomialTest, AgreesWithSciPy) {
  const std::vector<double> ref = scipy_p_values(kVoteCounts);
  ASSERT_EQ(ref.size(), kVoteCounts.size());
  double worst = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    const auto [k, n] = kVoteCounts[i];
    EXPECT_NEAR(binomial_test_two_sided(k, n), ref[i], 1e-9) << k << " of " << n;
    worst = std::max(worst, std::fabs(binomial_test_two_sided(k, n) - ref[i]));
  }
  std::printf("largest difference from SciPy: %.3g\n", worst);
}

TEST(BinomialTest, KnownValues) {
  EXPECT_DOUBLE_EQ(binomial_test_two_sided(0, 0), 1.0);
  EXPECT_NEAR(binomial_test_two_sided(0, 10), 2.0 / 1024, 1e-15);   // both all-one-side outcomes
  EXPECT_NEAR(binomial_test_two_sided(9, 10), 22.0 / 1024, 1e-15);  // 0, 1, 9, 10: (1 + 10) * 2
  EXPECT_NEAR(binomial_test_two_sided(5, 10), 1.0, 1e-12);
  // An uneven null: outcomes no more likely than the observed one, on both sides.
  EXPECT_NEAR(binomial_test_two_sided(0, 2, 0.25), 1.0, 1e-12);  // 9/16 is the likeliest outcome
  EXPECT_NEAR(binomial_test_two_sided(2, 2, 0.25), 1.0 / 16, 1e-15);
}

class TrialsFile : public ::testing::Test {
 protected:
  std::string write(const std::string& text) {
    test::write_file(path_, text);
    return path_;
  }
  std::string error_of(const std::string& text) {
    auto r = read_study_trials(write(text));
    return r ? std::string("(no error)") : r.error().message;
  }
  test::TempDir dir_;
  std::string path_ = dir_.path("trials.csv");
};

TEST_F(TrialsFile, TalliesPairsInEitherOrderAndScores) {
  auto t = read_study_trials(write(
      "participant,method_a,sigma_a,method_b,sigma_b,chosen,condition,score,validation\n"
      "p1,rmfr,2.6,kfr,2.6,a,,,0\n"
      "p1,kfr,2.6,rmfr,2.6,b,,,0\n"  // the same pair shown the other way round: rmfr again
      "p1,kfr,2.6,rmfr,2.6,a,,,0\n"
      "p1,rmfr,2.6,rmfr,3.0,b,,,\n"  // sigma makes it another pair
      "p1,rmfr,2.6,rmfr,2.6,a,,,1\n" // an identical validation pair: left out
      "p1,,,,,,uf,4,0\n"
      "p1,,,,,,uf,5,0\n"
      "p1,,,,,,nf,2,0\n"
      "p1,,,,,,nf,3,true\n"));
  ASSERT_TRUE(t) << t.error().message;
  const StudyStats st = compute_study_stats(*t);
  EXPECT_EQ(st.validation_trials, 2u);
  ASSERT_EQ(st.pairs.size(), 2u);
  EXPECT_EQ(st.pairs[0].first, "rmfr sigma=2.6");
  EXPECT_EQ(st.pairs[0].second, "kfr sigma=2.6");
  EXPECT_EQ(st.pairs[0].trials, 3u);
  EXPECT_EQ(st.pairs[0].votes_first, 2u);
  EXPECT_EQ(st.pairs[0].votes_second, 1u);
  EXPECT_NEAR(st.pairs[0].share_first, 2.0 / 3, 1e-15);
  EXPECT_NEAR(st.pairs[0].p_value, 1.0, 1e-12);
  EXPECT_EQ(st.pairs[1].second, "rmfr sigma=3.0");
  EXPECT_EQ(st.pairs[1].votes_second, 1u);
  ASSERT_EQ(st.scores.size(), 2u);
  EXPECT_EQ(st.scores[0].condition, "uf");
  EXPECT_DOUBLE_EQ(st.scores[0].mean, 4.5);
  EXPECT_NEAR(st.scores[0].sd, std::sqrt(0.5), 1e-15);
  EXPECT_EQ(st.scores[1].trials, 1u);
  EXPECT_DOUBLE_EQ(st.scores[1].mean, 2.0);
}

TEST_F(TrialsFile, BadRowsNameTheLineAndColumn) {
  const std::string p = path_;
  EXPECT_EQ(error_of("method_a,method_b,chosen\nrmfr,kfr,c\n"), p + ":2: chosen: 'c' is not a or b");
  EXPECT_EQ(error_of("method_a,method_b,chosen\nrmfr,kfr,a\nrmfr,kfr\n"), p + ":3: chosen: missing (row has 2 of 3 fields)");
  EXPECT_EQ(error_of("method_a,method_b,chosen\nrmfr,kfr,\n"), p + ":2: chosen: empty");
  EXPECT_EQ(error_of("method_a,method_b,chosen\n,kfr,a\n"), p + ":2: method_a: empty");
  EXPECT_EQ(error_of("method_a,method_b,chosen\nkfr,kfr,a\n"),
            p + ":2: method_b: the same condition 'kfr' on both sides; flag such rows in a validation column");
  EXPECT_EQ(error_of("method_a,method_b,chosen,validation\nrmfr,kfr,a,maybe\n"),
            p + ":2: validation: 'maybe' is not 0, 1, true or false");
  EXPECT_EQ(error_of("condition,score\nuf,6\n"), p + ":2: score: 6 is not a score from 1 to 5");
  EXPECT_EQ(error_of("condition,score\nuf,4.5\n"), p + ":2: score: '4.5' is not a number");
  EXPECT_EQ(error_of("condition,score\n,4\n"), p + ":2: condition: empty");
  EXPECT_EQ(error_of("method_a,method_b,chosen,condition,score\nrmfr,kfr,,,\n"),
            p + ":2: chosen: empty, and so is score: the row is no trial");
  EXPECT_EQ(error_of("method_a,chosen\nrmfr,a\n"),
            p + ":1: the header needs the columns method_a,method_b,chosen (choice trials) or condition,score (score trials)");
  EXPECT_EQ(error_of("method_a,method_b,chosen\n"), p + ": no trials: the file has a header only");
}

TEST(StudyStatsCli, PValuesAgreeWithSciPyAndBadRowsExitTwo) {
  // One pair of conditions per vote count, the sides shown in alternating order.
  test::TempDir d;
  std::string csv = "participant,method_a,f_a,method_b,f_b,chosen\n";
  for (std::size_t i = 0; i < kVoteCounts.size(); ++i) {
    const auto [k, n] = kVoteCounts[i];
    const std::string x = "rmfr," + std::to_string(i), y = "kfr," + std::to_string(i);
    for (std::uint64_t j = 0; j < n; ++j) {
      const bool vote_x = j < k, x_on_a = j % 2 == 0;
      csv += "p" + std::to_string(j % 7) + "," + (x_on_a ? x + "," + y : y + "," + x) + "," +
             ((vote_x == x_on_a) ? "a" : "b") + "\n";
    }
  }
  test::write_file(d.path("trials.csv"), csv);
  const auto r = test::run(test::bin("foveal") + " study stats --json " + d.path("trials.csv"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const std::vector<double> ref = scipy_p_values(kVoteCounts);
  ASSERT_EQ(ref.size(), kVoteCounts.size());
  ASSERT_EQ(j["pairs"].size(), kVoteCounts.size());
  for (std::size_t i = 0; i < kVoteCounts.size(); ++i) {
    const auto& p = j["pairs"][i];
    const auto [k, n] = kVoteCounts[i];
    EXPECT_EQ(p["first"], "rmfr f=" + std::to_string(i));
    EXPECT_EQ(p["trials"], n);
    EXPECT_EQ(p["votes_first"], k);
    EXPECT_EQ(p["votes_second"], n - k);
    EXPECT_NEAR(p["ratio_first"].get<double>(), static_cast<double>(k) / static_cast<double>(n), 1e-15);
    EXPECT_NEAR(p["p_value"].get<double>(), ref[i], 1e-9) << k << " of " << n;
  }

  test::write_file(d.path("bad.csv"), "method_a,method_b,chosen\nrmfr,kfr,a\nrmfr,kfr,yes\n");
  const auto bad = test::run(test::bin("foveal") + " study stats " + d.path("bad.csv"));
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_EQ(bad.err, "foveal: error: " + d.path("bad.csv") + ":3: chosen: 'yes' is not a or b\n");
  EXPECT_TRUE(bad.out.empty()) << bad.out;
}

TEST(StudyDesign, ConditionsParseAndNameTheirFaults) {
  auto c = parse_study_condition("rmfr:2/3:0.25", "--condition");
  ASSERT_TRUE(c) << c.error().message;
  EXPECT_EQ(c->method, "rmfr");
  EXPECT_DOUBLE_EQ(c->sigma_d, 2.0);
  EXPECT_DOUBLE_EQ(c->sigma_nd, 3.0);
  EXPECT_DOUBLE_EQ(c->f, 0.25);
  EXPECT_EQ(c->label(), "rmfr sigma_d=2 sigma_nd=3 f=0.25");
  EXPECT_EQ(parse_study_condition("kfr:2.6", "x")->label(), "kfr sigma=2.6 f=0.3");
  EXPECT_EQ(parse_study_condition("full", "x")->label(), "full");
  const char* suffix = " (expected METHOD[:SIGMA[/SIGMA_ND]][:F])";
  EXPECT_EQ(parse_study_condition("rmfr", "--condition").error().message,
            std::string("--condition: 'rmfr': a foveated method needs its level") + suffix);
  EXPECT_EQ(parse_study_condition("rmfr:0.5", "c").error().message, std::string("c: 'rmfr:0.5': sigma must be a number >= 1") + suffix);
  EXPECT_EQ(parse_study_condition("rmfr:3/2", "c").error().message, std::string("c: 'rmfr:3/2': sigma_nd must be a number >= sigma") + suffix);
  EXPECT_EQ(parse_study_condition("rmfr:2:0", "c").error().message, std::string("c: 'rmfr:2:0': f must be a number > 0") + suffix);
  EXPECT_EQ(parse_study_condition("full:2", "c").error().message, std::string("c: 'full:2': full resolution takes no level") + suffix);
}

TEST(StudyDesign, PlanIsSeededShuffledAndCountsValidationTrials) {
  StudyOptions o;
  o.scenes = {"a.gltf", "b.gltf"};
  o.conditions = {{"rmfr", 2.6, 2.6, 0.3}, {"kfr", 2.6, 2.6, 0.3}, {"hyperbolic", 2.6, 2.6, 0.3}};
  o.repeats = 4;
  o.validation_share = 0.2;
  auto p = plan_study(o);
  ASSERT_TRUE(p) << p.error().message;
  // 3 pairs x 2 scenes x 4 repeats = 24 tests; 0.2 / 0.8 x 24 = 6 validation trials.
  ASSERT_EQ(p->size(), 30u);
  int validations = 0, b_first = 0, in_place = 0;
  for (std::size_t i = 0; i < p->size(); ++i) {
    const PlannedTrial& t = (*p)[i];
    EXPECT_EQ(t.index, static_cast<int>(i + 1));
    if (t.validation) {
      ++validations;
      EXPECT_EQ(t.a.method, "full");
      EXPECT_EQ(t.b, o.validation_condition);
    }
    b_first += t.b_first;
    in_place += i < 6 && t.a.method == "rmfr" && t.b.method == "kfr";  // the unshuffled start
  }
  EXPECT_EQ(validations, 6);
  EXPECT_GT(b_first, 5);
  EXPECT_LT(b_first, 25);
  EXPECT_LT(in_place, 6);
  auto again = plan_study(o);
  for (std::size_t i = 0; i < p->size(); ++i) {
    EXPECT_EQ((*again)[i].a, (*p)[i].a);
    EXPECT_EQ((*again)[i].b, (*p)[i].b);
    EXPECT_EQ((*again)[i].scene, (*p)[i].scene);
    EXPECT_EQ((*again)[i].b_first, (*p)[i].b_first);
  }
  o.conditions.pop_back();
  o.conditions.pop_back();
  EXPECT_EQ(plan_study(o).error().message, "study: a 2AFC study needs at least two conditions");
}

TEST(StudySession, ValidationFailuresPauseThenDiscard) {
  StudyOptions o;
  o.design = StudyDesign::score;
  o.scenes = {"s"};
  o.conditions = {{"rmfr", 2, 2, 0.3}};
  o.repeats = 4;
  o.validation_share = 0.5;  // 4 tests, 4 validation trials
  o.max_validation_errors = 1;
  auto plan = plan_study(o);
  ASSERT_TRUE(plan);
  StudySession s(o, *plan);
  EXPECT_EQ(s.respond({6, {}}).error().message, "a score trial asks for 1 (very different) to 5 (no difference)");
  int failures = 0;
  while (!s.done()) {
    const bool validation = s.trial().validation;
    ASSERT_TRUE(s.respond({validation ? 1 : 4, 0.5}));  // identical frames called very different
    if (!validation) continue;
    ++failures;
    if (failures == 1) {
      EXPECT_TRUE(s.pause_requested());
      EXPECT_FALSE(s.discarded());
      s.resume();
      EXPECT_FALSE(s.pause_requested());
    }
  }
  EXPECT_EQ(failures, 2);
  EXPECT_TRUE(s.discarded());  // 2 > max_validation_errors
  EXPECT_EQ(s.pauses(), 1);
  EXPECT_LE(s.results().size(), s.planned());
  EXPECT_EQ(s.respond({5, {}}).error().message, "the study is already complete");
  const std::string csv = study_trials_csv(s);
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')), s.results().size() + 1);
}

TEST(SigmaEstimates, CrossingsAndBounds) {
  auto trial = [](double d, double nd, int score) { return ScoreTrial{"rmfr", score, 0, d, nd}; };
  // Uniform 1.5: 5, 2.0: 4.5 and 3.5 (mean 4), 3.0: 2 -> crossing between 2.0 (4.0 holds) and 3.0.
  std::vector<ScoreTrial> t = {trial(1.5, 1.5, 5), trial(2, 2, 5), trial(2, 2, 3), trial(3, 3, 2),
                               trial(2, 2.5, 5), trial(2, 3.5, 3), trial(2.5, 4, 1)};
  t.push_back(ScoreTrial{"kfr sigma=3", 5, 0, 3.0, 3.0});  // another method: its own estimates
  const std::vector<SigmaEstimates> all = estimate_sigmas(t, 4.0);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[1].method, "kfr");
  EXPECT_EQ(all[1].sigma_uf->bound, EstimateBound::at_least);
  SigmaEstimates e = all[0];
  EXPECT_EQ(e.method, "rmfr");
  ASSERT_TRUE(e.sigma_uf);
  EXPECT_EQ(e.sigma_uf->bound, EstimateBound::interpolated);
  EXPECT_NEAR(e.sigma_uf->sigma, 2.0, 1e-12);  // the mean at 2.0 is exactly the threshold: it still holds
  ASSERT_TRUE(e.sigma_nf);
  EXPECT_EQ(e.sigma_nf_at_sigma_d, 2.0);  // the largest tested sigma_d <= sigma_UF with a non-dominant series
  // sigma_d 2: 4 at 2.0 (uniform), 5 at 2.5, 3 at 3.5: crossing at 2.5 + (5 - 4) / (5 - 3) x 1.0.
  EXPECT_NEAR(e.sigma_nf->sigma, 3.0, 1e-12);
  EXPECT_EQ(e.levels.size(), 6u);

  e = estimate_sigmas(std::vector<ScoreTrial>{trial(2, 2, 5), trial(3, 3, 5)}, 4.0)[0];
  EXPECT_EQ(e.sigma_uf->bound, EstimateBound::at_least);
  EXPECT_DOUBLE_EQ(e.sigma_uf->sigma, 3.0);
  EXPECT_FALSE(e.sigma_nf);
  e = estimate_sigmas(std::vector<ScoreTrial>{trial(2, 2, 2), trial(3, 3, 1)}, 4.0)[0];
  EXPECT_EQ(e.sigma_uf->bound, EstimateBound::below_range);
  EXPECT_DOUBLE_EQ(e.sigma_uf->sigma, 2.0);
  EXPECT_TRUE(estimate_sigmas(std::vector<ScoreTrial>{ScoreTrial{"no levels", 3, 0, {}, {}}}, 4.0).empty());
  // Only a non-dominant series: no sigma_UF, so no sigma_NF either.
  e = estimate_sigmas(std::vector<ScoreTrial>{trial(2, 3, 5)}, 4.0)[0];
  EXPECT_FALSE(e.sigma_uf);
  EXPECT_FALSE(e.sigma_nf);
}

}  // namespace
}  // namespace foveal
