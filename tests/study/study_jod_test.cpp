// `foveal study run`'s predicted JOD per condition (conditions.csv, summary.json beside
// the answers): present, finite, lower for a coarser level; left out by --no-jod.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "csv_rows.hpp"
#include "test_support.hpp"

using namespace foveal;

namespace {

const auto rows_of = test::csv_lines;

std::string study(const std::string& design, const std::string& conditions, const std::string& answers_file,
                  const std::string& out) {
  return test::bin("foveal") + " study run --design " + design + " --scene pattern:noise" + conditions +
         " --repeats 1 --validation-share 0 --size 320x180 --present-s 0.01 --blank-s 0 --answers " + answers_file +
         " --out " + out + " --json";
}

}  // namespace

TEST(StudyJod, ConditionsCarryAFinitePredictedJodThatFallsWithTheLevel) {
  test::TempDir d;
  test::write_file(d.path("answers.txt"), "5\n3\n4\n");
  // An EFR condition with the uniform one's sigma_d: the two must not be mixed up.
  const std::string conditions = " --condition rmfr:1.5 --condition rmfr:4 --condition rmfr:1.5/4";
  const auto r = test::run(study("score", conditions, d.path("answers.txt"), d.path("out")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = rows_of(test::read_file(d.path("out/conditions.csv")));
  ASSERT_EQ(rows.size(), 4u);
  const std::vector<std::string> header = {"scene", "condition", "method", "sigma_d", "sigma_nd", "f",
                                           "predicted_jod", "predicted_jod_left", "predicted_jod_right"};
  EXPECT_EQ(rows[0], header);
  std::map<std::string, double> jod;
  for (std::size_t i = 1; i < rows.size(); ++i) {
    ASSERT_EQ(rows[i].size(), header.size());
    EXPECT_EQ(rows[i][0], "pattern:noise");
    for (std::size_t c = 6; c < 9; ++c) {
      const double v = std::stod(rows[i][c]);
      EXPECT_TRUE(std::isfinite(v) && v <= 10.0) << rows[i][1] << " " << header[c] << " " << v;
    }
    jod[rows[i][1]] = std::stod(rows[i][6]);
  }
  ASSERT_EQ(jod.size(), 3u);
  const std::string fine = "rmfr sigma=1.5 f=0.3", coarse = "rmfr sigma=4 f=0.3", efr = "rmfr sigma_d=1.5 sigma_nd=4 f=0.3";
  ASSERT_TRUE(jod.count(fine) && jod.count(coarse) && jod.count(efr));
  EXPECT_LT(jod[coarse], jod[fine]) << "a coarser level is predicted to look worse";
  EXPECT_LT(jod[coarse], 9.9) << "sigma 4 is visibly degraded";
  EXPECT_NE(jod[efr], jod[fine]);

  // Beside the participant's answers in the summary: the score of each condition.
  const auto summary = nlohmann::json::parse(r.out);
  ASSERT_EQ(summary["scores"].size(), 3u);
  for (const auto& s : summary["scores"])
    EXPECT_NEAR(s["predicted_jod"].get<double>(), jod[s["condition"].get<std::string>()], 1e-4) << s.dump();
  EXPECT_EQ(summary["predicted_jod"]["conditions"].size(), 3u);
  EXPECT_GT(summary["predicted_jod"]["ppd"][0].get<double>(), 0.0) << summary["predicted_jod"].dump();

  // study stats reads it back beside the same trials: the same figures.
  const auto st = test::run(test::bin("foveal") + " study stats " + d.path("out/trials.csv") + " --conditions " +
                            d.path("out/conditions.csv") + " --json");
  ASSERT_EQ(st.exit_code, 0) << st.err;
  for (const auto& s : nlohmann::json::parse(st.out)["scores"])
    EXPECT_NEAR(s["predicted_jod"].get<double>(), jod[s["condition"].get<std::string>()], 1e-4) << s.dump();

  // --no-jod: no conditions.csv, nothing predicted in the summary.
  const auto no = test::run(study("score", conditions + " --no-jod", d.path("answers.txt"), d.path("no")));
  ASSERT_EQ(no.exit_code, 0) << no.err;
  EXPECT_FALSE(std::filesystem::exists(d.path("no/conditions.csv")));
  EXPECT_FALSE(nlohmann::json::parse(no.out).contains("predicted_jod"));
  EXPECT_FALSE(nlohmann::json::parse(no.out)["scores"][0].contains("predicted_jod"));
}

TEST(StudyJod, TwoAfcPairsCarryBothSidesPredictedJod) {
  test::TempDir d;
  test::write_file(d.path("answers.txt"), "1\n");
  const auto r = test::run(study("2afc", " --condition rmfr:3 --condition full", d.path("answers.txt"), d.path("out")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(r.out);
  ASSERT_EQ(summary["pairs"].size(), 1u);
  const auto& p = summary["pairs"][0];
  for (const char* side : {"first", "second"}) {
    ASSERT_TRUE(p["predicted_jod_" + std::string(side)].is_number()) << p.dump();
    const double v = p["predicted_jod_" + std::string(side)].get<double>();
    if (p[side].get<std::string>().rfind("full", 0) == 0) EXPECT_NEAR(v, 10.0, 1e-6) << "full against itself";
    else EXPECT_LT(v, 10.0);
  }
}
