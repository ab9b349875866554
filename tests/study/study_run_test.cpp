// `foveal study run` end to end, scripted and headless (EGL, small size): a 2AFC study
// and a random test produce the trials CSV that `foveal study stats` reads; validation
// trials, the pause after a failed one, discarding, the seeded order. The expected
// answers come from the same plan the command makes (plan_study), so a different plan
// in the command fails the test.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/study/study_session.hpp"
#include "csv_rows.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

const std::string kScene = "pattern:noise";

StudyOptions two_afc_options() {
  StudyOptions o;
  o.design = StudyDesign::two_afc;
  o.participant = "p07";
  o.scenes = {kScene};
  o.conditions = {{"rmfr", 2.6, 2.6, 0.3}, {"kfr", 2.6, 2.6, 0.3}, {"full", 1, 1, 0.3}};
  o.repeats = 2;
  o.validation_share = 0.25;
  return o;
}

StudyOptions score_options() {
  StudyOptions o;
  o.design = StudyDesign::score;
  o.participant = "p08";
  o.scenes = {kScene};
  o.conditions = {{"rmfr", 1.5, 1.5, 0.3}, {"rmfr", 2.0, 2.0, 0.3}, {"rmfr", 2.5, 2.5, 0.3},
                  {"rmfr", 2.0, 3.0, 0.3}, {"rmfr", 2.0, 4.0, 0.3}};
  o.repeats = 2;
  o.validation_share = 0.3;
  return o;
}

std::string common_args(const StudyOptions& o, const std::string& conditions) {
  return test::bin("foveal") + " study run --design " + study_design_name(o.design) + " --participant " +
         o.participant + " --scene " + kScene + conditions + " --repeats " + std::to_string(o.repeats) +
         " --validation-share " + std::to_string(o.validation_share) + " --size 96x48 --present-s 0.01 --blank-s 0";
}

std::string responses(const std::vector<int>& keys) {
  std::string s = "# one response per trial\n";
  for (int k : keys) s += std::to_string(k) + "@0.5\n";
  return s;
}

const auto csv_rows = test::csv_lines;

TEST(StudyRun, TwoAfcScriptedEndToEnd) {
  const StudyOptions o = two_afc_options();
  auto plan = plan_study(o);
  ASSERT_TRUE(plan) << plan.error().message;
  ASSERT_EQ(plan->size(), 8u);  // 3 pairs x 2 repeats + round(0.25 / 0.75 x 6) = 2 validation trials
  // Validation: full resolution, the right answer. Tests: the side with rmfr, else the first.
  std::vector<int> keys;
  for (const PlannedTrial& t : *plan) {
    const bool want_a = t.validation || t.a.method == "rmfr" || t.b.method != "rmfr";
    keys.push_back(want_a != t.b_first ? 1 : 2);
  }
  test::TempDir d;
  test::write_file(d.path("answers.txt"), responses(keys));
  const std::string cmd = common_args(o, " --condition rmfr:2.6 --condition kfr:2.6 --condition full") +
                          " --answers " + d.path("answers.txt") + " --frames-out " + d.path("frames") + " --out " +
                          d.path("out") + " --json";
  const auto r = test::run(cmd);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(test::read_file(d.path("out/summary.json")));
  EXPECT_EQ(summary, nlohmann::json::parse(r.out));
  EXPECT_EQ(summary["trials"]["answered"], 8);
  EXPECT_EQ(summary["validation"]["trials"], 2);
  EXPECT_EQ(summary["validation"]["failures"], 0);
  EXPECT_EQ(summary["pauses"], 0);
  EXPECT_EQ(summary["discarded"], false);
  EXPECT_EQ(summary["seed"], study_seed(o));

  const auto rows = csv_rows(test::read_file(d.path("out/trials.csv")));
  ASSERT_EQ(rows.size(), 9u);
  EXPECT_EQ(rows[0][0], "participant");
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const PlannedTrial& t = (*plan)[i - 1];
    ASSERT_EQ(rows[i].size(), rows[0].size());
    EXPECT_EQ(rows[i][0], "p07");
    EXPECT_EQ(rows[i][1], kScene);
    EXPECT_EQ(rows[i][2], std::to_string(i));
    EXPECT_EQ(rows[i][4], t.a.method);
    EXPECT_EQ(rows[i][7], t.b.method);
    EXPECT_EQ(rows[i][10], t.b_first ? "ba" : "ab");
    EXPECT_EQ(rows[i][16], "0.500");
    EXPECT_EQ(rows[i][17], t.validation ? "1" : "0");
    EXPECT_EQ(rows[i][18], "0");
    // Both presentations were rendered; a validation pair (full vs sigma 6) differs.
    const std::string f1 = test::read_file(d.path("frames/trial_00" + std::to_string(i) + "_1.png"));
    const std::string f2 = test::read_file(d.path("frames/trial_00" + std::to_string(i) + "_2.png"));
    ASSERT_FALSE(f1.empty());
    EXPECT_NE(f1, f2) << "trial " << i;
  }

  // study stats reads it: rmfr won every one of its pairs, validation rows left out.
  const auto st = test::run(test::bin("foveal") + " study stats --json " + d.path("out/trials.csv"));
  ASSERT_EQ(st.exit_code, 0) << st.err;
  const auto j = nlohmann::json::parse(st.out);
  EXPECT_EQ(j["validation_trials"], 2);
  ASSERT_EQ(j["pairs"].size(), 3u);
  for (const auto& p : j["pairs"]) {
    EXPECT_EQ(p["trials"], 2);
    const std::string first = p["first"], second = p["second"];
    if (first.starts_with("rmfr")) {
      EXPECT_EQ(p["votes_first"], 2) << first << " vs " << second;
    } else if (second.starts_with("rmfr")) {
      EXPECT_EQ(p["votes_second"], 2) << first << " vs " << second;
    }
  }

  // The same participant and seed: the same trials; another participant: another order.
  const auto again = test::run(cmd.substr(0, cmd.find(" --frames-out")) + " --out " + d.path("again"));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(test::read_file(d.path("again/trials.csv")), test::read_file(d.path("out/trials.csv")));
  StudyOptions other = o;
  other.participant = "p09";
  auto other_plan = plan_study(other);
  ASSERT_TRUE(other_plan);
  bool same_order = true;
  for (std::size_t i = 0; i < plan->size(); ++i)
    same_order &= (*plan)[i].a == (*other_plan)[i].a && (*plan)[i].b == (*other_plan)[i].b &&
                  (*plan)[i].b_first == (*other_plan)[i].b_first;
  EXPECT_FALSE(same_order);
}

TEST(StudyRun, RandomTestScriptedEndToEndWithSigmaEstimates) {
  const StudyOptions o = score_options();
  auto plan = plan_study(o);
  ASSERT_TRUE(plan) << plan.error().message;
  ASSERT_EQ(plan->size(), 14u);  // 5 conditions x 2 + round(0.3 / 0.7 x 10) = 4 validation trials
  // Scores: 5 up to sigma 2 for both eyes, 3 at 2.5; with the dominant eye at 2: 4 at
  // sigma_nd 3, 2 at 4. Validation (identical frames): 5, except one 3 (a failure: a pause).
  std::vector<int> keys;
  int validation_seen = 0;
  for (const PlannedTrial& t : *plan) {
    if (t.validation) keys.push_back(validation_seen++ == 1 ? 3 : 5);
    else if (t.b.uniform()) keys.push_back(t.b.sigma_d <= 2.0 ? 5 : 3);
    else keys.push_back(t.b.sigma_nd <= 3.0 ? 4 : 2);
  }
  test::TempDir d;
  test::write_file(d.path("answers.txt"), responses(keys));
  const std::string conditions =
      " --condition rmfr:1.5 --condition rmfr:2 --condition rmfr:2.5 --condition rmfr:2/3 --condition rmfr:2/4";
  const auto r = test::run(common_args(o, conditions) + " --answers " + d.path("answers.txt") + " --frames-out " +
                           d.path("frames") + " --out " + d.path("out") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["validation"]["trials"], 4);
  EXPECT_EQ(summary["validation"]["failures"], 1);
  EXPECT_EQ(summary["pauses"], 1);
  const auto rows = csv_rows(test::read_file(d.path("out/trials.csv")));
  ASSERT_EQ(rows.size(), 15u);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    const PlannedTrial& t = (*plan)[i - 1];
    EXPECT_EQ(rows[i][3], "score");
    EXPECT_EQ(rows[i][12], t.b.label());
    EXPECT_EQ(rows[i][15], std::to_string(keys[i - 1]));
    char name[2][64];
    for (int p = 0; p < 2; ++p) std::snprintf(name[p], sizeof name[p], "frames/trial_%03zu_%d.png", i, p + 1);
    const std::string f1 = test::read_file(d.path(name[0])), f2 = test::read_file(d.path(name[1]));
    ASSERT_FALSE(f1.empty());
    // Validation trials show identical frames; the others a foveated frame and full.
    if (t.validation) {
      EXPECT_EQ(f1, f2) << "trial " << i;
    } else {
      EXPECT_NE(f1, f2) << "trial " << i;
    }
  }

  const auto st = test::run(test::bin("foveal") + " study stats --json " + d.path("out/trials.csv"));
  ASSERT_EQ(st.exit_code, 0) << st.err;
  const auto j = nlohmann::json::parse(st.out);
  EXPECT_EQ(j["validation_trials"], 4);
  ASSERT_EQ(j["scores"].size(), 5u);
  ASSERT_EQ(j["sigma_estimates"].size(), 1u);
  const auto& e = j["sigma_estimates"][0];
  EXPECT_EQ(e["method"], "rmfr");
  // Uniform: 5 at 2.0, 3 at 2.5: the threshold 4 is crossed half way, at 2.25.
  EXPECT_NEAR(e["sigma_uf"]["sigma"].get<double>(), 2.25, 1e-12);
  EXPECT_EQ(e["sigma_uf"]["bound"], "interpolated");
  // Dominant eye at 2.0: 5 at sigma_nd 2, 4 at 3, 2 at 4: the threshold holds at 3.
  EXPECT_NEAR(e["sigma_nf"]["sigma"].get<double>(), 3.0, 1e-12);
  EXPECT_EQ(e["sigma_nf"]["at_sigma_d"], 2.0);
}

TEST(StudyRun, ParticipantPastTheErrorCountIsDiscarded) {
  const StudyOptions o = score_options();
  auto plan = plan_study(o);
  ASSERT_TRUE(plan);
  std::vector<int> keys;
  for (const PlannedTrial& t : *plan) {
    keys.push_back(t.validation ? 1 : 4);  // every identical pair called very different
    if (t.validation && std::count(keys.begin(), keys.end(), 1) == 3) break;  // the third failure ends it
  }
  test::TempDir d;
  test::write_file(d.path("answers.txt"), responses(keys));
  const std::string conditions =
      " --condition rmfr:1.5 --condition rmfr:2 --condition rmfr:2.5 --condition rmfr:2/3 --condition rmfr:2/4";
  const auto r = test::run(common_args(o, conditions) + " --answers " + d.path("answers.txt") + " --out " + d.path("out"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("participant p08's data discarded: 3 failed validation trials (at most 2 allowed)"), std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(d.path("out/trials.csv")));
  const auto summary = nlohmann::json::parse(test::read_file(d.path("out/summary.json")));
  EXPECT_EQ(summary["discarded"], true);
  EXPECT_EQ(summary["validation"]["failures"], 3);
  EXPECT_EQ(summary["pauses"], 2);

  // One response more than the run takes is an error naming the line.
  keys.push_back(5);
  test::write_file(d.path("more.txt"), responses(keys));
  const auto more = test::run(common_args(o, conditions) + " --answers " + d.path("more.txt") + " --out " + d.path("more"));
  EXPECT_EQ(more.exit_code, 2);
  EXPECT_NE(more.err.find("more.txt:" + std::to_string(keys.size() + 1) +
                          ": more responses than trials (the participant was discarded before this one)"),
            std::string::npos)
      << more.err;
}

TEST(StudyRun, BadResponsesAndOptionsExitTwoWithoutOutput) {
  const StudyOptions o = two_afc_options();
  const std::string conditions = " --condition rmfr:2.6 --condition kfr:2.6 --condition full";
  test::TempDir d;
  test::write_file(d.path("short.txt"), "1 2\n1\n");
  auto r = test::run(common_args(o, conditions) + " --answers " + d.path("short.txt") + " --out " + d.path("out"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "foveal: error: " + d.path("short.txt") + ": responses ended at trial 4 of 8\n");
  EXPECT_FALSE(std::filesystem::exists(d.path("out/trials.csv")));
  EXPECT_FALSE(std::filesystem::exists(d.path("out/summary.json")));

  test::write_file(d.path("three.txt"), "1\n3\n");
  r = test::run(common_args(o, conditions) + " --answers " + d.path("three.txt") + " --out " + d.path("out"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "foveal: error: " + d.path("three.txt") + ":2: trial 2: a 2AFC trial asks for 1 (first) or 2 (second)\n");

  test::write_file(d.path("word.txt"), "1\nyes\n");
  r = test::run(common_args(o, conditions) + " --answers " + d.path("word.txt") + " --out " + d.path("out"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "foveal: error: " + d.path("word.txt") + ":2: 'yes' is not a response (1 to 5, optionally @SECONDS)\n");

  r = test::run(common_args(o, " --condition rmfr:2.6 --condition warp:2") + " --answers " + d.path("word.txt") +
                " --out " + d.path("out"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("study: condition 'warp sigma=2 f=0.3': "), std::string::npos) << r.err;
  r = test::run(common_args(o, " --condition rmfr:2/3 --condition kfr:2.6") + " --answers " + d.path("word.txt") +
                " --out " + d.path("out"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "foveal: error: --condition: 'rmfr:2/3': a 2AFC condition has one level for both eyes\n");
  EXPECT_FALSE(std::filesystem::exists(d.path("out/trials.csv")));
}


// The headset mode on a virtual X server (Xvfb, xdotool: scripts/bootstrap.sh), with
// real key presses: a 2AFC test trial and a validation trial, answered as planned.
TEST(StudyRun, HeadsetWindowTakesTheKeyboard) {
  for (const char* tool : {"/usr/bin/xvfb-run", "/usr/bin/xdotool"})
    ASSERT_TRUE(std::filesystem::exists(tool)) << tool << " is missing: install xvfb, xauth and xdotool";
  StudyOptions o = two_afc_options();
  o.conditions = {{"rmfr", 2.6, 2.6, 0.3}, {"kfr", 2.6, 2.6, 0.3}};
  o.repeats = 1;
  o.validation_share = 0.5;
  auto plan = plan_study(o);
  ASSERT_TRUE(plan);
  ASSERT_EQ(plan->size(), 2u);
  // Side a both times (the test trial's rmfr, the validation trial's full): the first
  // presentation (key 1) or the second (the right arrow), each once the window asks.
  test::TempDir d;
  std::string keys;
  for (const PlannedTrial& t : *plan)
    keys += "until grep -q 'trial " + std::to_string(t.index) + " of 2: waiting' " + d.path("err.txt") +
            "; do sleep 0.05; done; xdotool key " + (t.b_first ? "Right" : "1") + "; ";
  const std::string run = common_args(o, " --condition rmfr:2.6 --condition kfr:2.6") + " --out " + d.path("out") +
                          " --json > " + d.path("out.json") + " 2> " + d.path("err.txt") + " & P=\\$!; " +
                          // Escaped: the inner shell under xvfb-run expands these, not the outer one.
                          "W=\\$(xdotool search --sync --onlyvisible --name 'foveal study' | head -1); "
                          "xdotool windowfocus --sync \\$W; " + keys + "wait \\$P";
  const auto r = test::run("timeout 120 xvfb-run -a -s '-screen 0 1280x720x24' sh -c \"" + run + "\"");
  ASSERT_EQ(r.exit_code, 0) << r.err << test::read_file(d.path("err.txt"));
  const auto summary = nlohmann::json::parse(test::read_file(d.path("out.json")));
  EXPECT_EQ(summary["mode"], "headset");
  EXPECT_EQ(summary["validation"]["failures"], 0);
  const auto rows = csv_rows(test::read_file(d.path("out/trials.csv")));
  ASSERT_EQ(rows.size(), 3u);
  for (std::size_t i = 1; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i][11], "a") << "trial " << i;
    EXPECT_GT(std::stod(rows[i][16]), 0.0) << "trial " << i;  // a measured response time
  }
}

}  // namespace
}  // namespace foveal
