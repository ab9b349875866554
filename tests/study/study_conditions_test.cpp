// conditions.csv read back (read_predicted_jod) and `foveal study stats --conditions`:
// each condition's predicted JOD beside its votes and scores, under both label forms.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "foveal/study/study_conditions.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

const char* kConditions =
    "scene,condition,method,sigma_d,sigma_nd,f,predicted_jod,predicted_jod_left,predicted_jod_right\n"
    "s1,rmfr sigma=2 f=0.3,rmfr,2,2,0.3,9.5000,9.4000,9.6000\n"
    "s2,rmfr sigma=2 f=0.3,rmfr,2,2,0.3,9.0000,8.9000,9.1000\n"
    "s1,full,full,1,1,,10.0000,10.0000,10.0000\n"
    "s1,rmfr sigma_d=2 sigma_nd=3 f=0.3,rmfr,2,3,0.3,9.2000,9.3000,9.1000\n";

TEST(StudyConditions, MeansOverScenesUnderBothLabels) {
  test::TempDir d;
  test::write_file(d.path("c.csv"), kConditions);
  auto m = read_predicted_jod(d.path("c.csv"));
  ASSERT_TRUE(m) << m.error().message;
  ASSERT_TRUE(m->count("rmfr sigma=2 f=0.3"));
  EXPECT_DOUBLE_EQ(m->at("rmfr sigma=2 f=0.3").jod, 9.25);
  EXPECT_DOUBLE_EQ(m->at("rmfr sigma=2 f=0.3").left, 9.15);
  EXPECT_EQ(m->at("rmfr sigma=2 f=0.3").scenes, 2) << "a uniform label is counted once per row";
  EXPECT_DOUBLE_EQ(m->at("full").jod, 10.0);
  EXPECT_DOUBLE_EQ(m->at("full sigma=1 f=").jod, 10.0);  // how study stats labels a 2AFC side
  EXPECT_DOUBLE_EQ(m->at("rmfr sigma_d=2 sigma_nd=3 f=0.3").right, 9.1);
}

TEST(StudyConditions, StatsPrintsThePredictionBesideVotesAndScores) {
  test::TempDir d;
  test::write_file(d.path("c.csv"), kConditions);
  test::write_file(d.path("t.csv"),
                   "method_a,sigma_a,f_a,method_b,sigma_b,f_b,chosen,condition,score,sigma_d,sigma_nd\n"
                   "rmfr,2,0.3,full,1,,b,,,,\n"
                   "full,1,,rmfr,2,0.3,a,,,,\n"
                   ",,,,,,,rmfr sigma_d=2 sigma_nd=3 f=0.3,4,2,3\n"
                   ",,,,,,,kfr sigma=2 f=0.3,3,2,2\n");
  const std::string stats = test::bin("foveal") + " study stats " + d.path("t.csv");
  auto r = test::run(stats + " --conditions " + d.path("c.csv") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["pairs"].size(), 1u);
  EXPECT_DOUBLE_EQ(j["pairs"][0]["predicted_jod_first"].get<double>(), 9.25) << j["pairs"][0].dump();
  EXPECT_DOUBLE_EQ(j["pairs"][0]["predicted_jod_second"].get<double>(), 10.0);
  ASSERT_EQ(j["scores"].size(), 2u);
  for (const auto& s : j["scores"]) {
    if (s["condition"] == "kfr sigma=2 f=0.3") EXPECT_TRUE(s["predicted_jod"].is_null()) << "not in the file";
    else EXPECT_DOUBLE_EQ(s["predicted_jod"].get<double>(), 9.2);
  }
  auto text = test::run(stats + " --conditions " + d.path("c.csv"));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("JOD (predicted)"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("9.25 :    10.00"), std::string::npos) << text.out;
  // Without --conditions: no JOD at all.
  auto plain = test::run(stats + " --json");
  ASSERT_EQ(plain.exit_code, 0);
  EXPECT_FALSE(nlohmann::json::parse(plain.out)["scores"][0].contains("predicted_jod"));
}

TEST(StudyConditions, BadFilesAreRefusedNamingFileLineAndColumn) {
  test::TempDir d;
  test::write_file(d.path("t.csv"), "condition,score\nfull,5\n");
  const std::string stats = test::bin("foveal") + " study stats " + d.path("t.csv") + " --conditions ";
  test::write_file(d.path("nojod.csv"), "scene,condition,method,sigma_d,f\ns,full,full,1,\n");
  auto r = test::run(stats + d.path("nojod.csv"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("predicted_jod"), std::string::npos) << r.err;
  test::write_file(d.path("nan.csv"), "condition,method,sigma_d,f,predicted_jod\nfull,full,1,,nan\n");
  r = test::run(stats + d.path("nan.csv"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("nan.csv:2"), std::string::npos) << r.err;
  test::write_file(d.path("empty.csv"), "condition,method,sigma_d,f,predicted_jod\n");
  r = test::run(stats + d.path("empty.csv"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("header only"), std::string::npos) << r.err;
  r = test::run(stats + d.path("missing.csv"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("missing.csv"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace foveal
