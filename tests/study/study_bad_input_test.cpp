// Crafted study inputs (issue 27, item 7): `study stats --threshold nan`, a column named
// twice, a NUL inside a label, a scripted response time of 1e308.
#include <gtest/gtest.h>

#include <filesystem>

#include "foveal/study/study_session.hpp"
#include "foveal/study/study_stats.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

std::string error_of(const test::TempDir& d, const std::string& text) {
  test::write_file(d.path("trials.csv"), text);
  auto r = read_study_trials(d.path("trials.csv"));
  return r ? std::string("(no error)") : r.error().message;
}

TEST(StudyBadInput, ThresholdNanExitsTwo) {
  test::TempDir d;
  test::write_file(d.path("t.csv"), "condition,score\nuf,4\n");
  for (const char* t : {"nan", "NaN", "-nan"}) {
    SCOPED_TRACE(t);
    auto r = test::run(test::bin("foveal") + " study stats --threshold " + t + " " + d.path("t.csv"));
    EXPECT_EQ(r.exit_code, 2) << r.out;
    EXPECT_NE(r.err.find("--threshold: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(" is not a mean score in [1, 5]"), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
  }
  EXPECT_EQ(test::run(test::bin("foveal") + " study stats --threshold 5 " + d.path("t.csv")).exit_code, 0);
}

TEST(StudyBadInput, AColumnNamedTwiceIsRefused) {
  test::TempDir d;
  const std::string p = d.path("trials.csv");
  EXPECT_EQ(error_of(d, "method_a,method_b,chosen,chosen\nrmfr,kfr,a,b\n"),
            p + ":1: column 'chosen' appears twice in the header (columns 3 and 4)");
  EXPECT_EQ(error_of(d, "condition,score,sigma_a,score\nuf,4,1,5\n"),
            p + ":1: column 'score' appears twice in the header (columns 2 and 4)");
  EXPECT_EQ(error_of(d, "condition,score,,\nuf,4,,\n"), "(no error)");  // empty names from trailing commas name nothing
}

TEST(StudyBadInput, ControlCharactersInALabelAreRefusedNamingLineAndColumn) {
  test::TempDir d;
  const std::string p = d.path("trials.csv");
  // A NUL cut "rm\0fr" to "rm" in the printed table.
  EXPECT_EQ(error_of(d, std::string("method_a,method_b,chosen\nrmfr,kfr,a\nrm\0fr,kfr,a\n", 48)),
            p + ":3: method_a: byte 3 of 'rm\\x00fr' is a control character");
  EXPECT_EQ(error_of(d, std::string("method_a,f_a,method_b,f_b,chosen\nrmfr,0.3,kfr,0\x01,a\n")),
            p + ":2: f_b: byte 2 of '0\\x01' is a control character");
  EXPECT_EQ(error_of(d, std::string("condition,score\nu\0f,4\n", 22)), p + ":2: condition: byte 2 of 'u\\x00f' is a control character");
  const std::string long_label = "method_a,method_b,chosen\n" + std::string(300, 'm') + ",kfr,a\n";
  EXPECT_EQ(error_of(d, long_label), p + ":2: method_a: 300 bytes; a label has at most 256");
}

TEST(StudyBadInput, AScriptedResponseTimeIsAtMostAnHour) {
  for (const char* word : {"1@1e308", "2@3600.001", "3@86400"}) {
    SCOPED_TRACE(word);
    auto r = parse_study_response(word);
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().message.find(" s is more than 3600 s"), std::string::npos) << r.error().message;
  }
  auto hour = parse_study_response("4@3600");
  ASSERT_TRUE(hour) << hour.error().message;
  EXPECT_EQ(hour->response_s, 3600.0);
  auto r = parse_study_response("9" + std::string(100000, 'x'));
  ASSERT_FALSE(r);
  EXPECT_LT(r.error().message.size(), 200u) << "the word is quoted whole";
}

}  // namespace
}  // namespace foveal
