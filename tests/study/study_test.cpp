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

}  // namespace
}  // namespace foveal
