// `foveal log quality` end to end: the real Vive Pro Eye recordings against an
// independent NumPy computation, accuracy on a log with known targets and offsets, and
// bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

#include <nlohmann/json.hpp>

#include "foveal/core/gaze_log.hpp"
#include "foveal/quality/fick_angles.hpp"
#include "test_support.hpp"
#include "turned_direction.hpp"

namespace foveal {
namespace {

std::string foveal_cli(const std::string& args) { return test::bin("foveal") + " " + args; }

void expect_close(double ours, double theirs, const std::string& what) {
  EXPECT_NEAR(ours, theirs, 1e-9 * std::max(1.0, std::fabs(theirs))) << what;
}

class RealRecording : public ::testing::TestWithParam<const char*> {};

TEST_P(RealRecording, MatchesNumPyPerEye) {
  test::TempDir d;
  const std::string log = d.path("log.csv");
  const auto imp = test::run(foveal_cli("import --from sranipal " +
                                        test::source_path(std::string("data/gaze/vive_pro_eye/") + GetParam()) +
                                        " --out " + log));
  ASSERT_EQ(imp.exit_code, 0) << imp.err;
  for (const std::string window : {"", "2 8.5"}) {
    const std::string opts = window.empty() ? "" : " --start 2 --end 8.5";
    const auto ours = test::run(foveal_cli("log quality --json " + log + opts));
    ASSERT_EQ(ours.exit_code, 0) << ours.err;
    const auto ref = test::run(std::string(FOVEAL_SYSTEM_PYTHON3) + " " +
                               test::source_path("tests/quality/quality_reference.py") + " " + log + " " + window);
    ASSERT_EQ(ref.exit_code, 0) << "the NumPy reference failed (python3-numpy installed? scripts/bootstrap.sh):\n"
                                << ref.err;
    const auto q = nlohmann::json::parse(ours.out), r = nlohmann::json::parse(ref.out);
    expect_close(q["window"]["duration_s"], r["duration_s"], "duration " + window);
    for (const char* eye : {"left", "right"}) {
      const auto& c = q["channels"][eye];
      const auto& e = r[eye];
      EXPECT_EQ(c["valid"], e["valid"]) << eye;
      EXPECT_GT(c["valid"].get<int>(), 100) << eye;
      for (const char* m : {"rms_s2s_deg", "std_deg", "bcea_deg2", "data_loss_pct", "effective_frequency_hz"})
        expect_close(c[m], e[m], std::string(eye) + " " + m + " window '" + window + "'");
    }
  }
}

INSTANTIATE_TEST_SUITE_P(ViveProEye, RealRecording,
                         ::testing::Values("TESTNA01_2D_Fist3.csv", "TESTNA05_360VR_Spread7.csv",
                                           "TESTNA15_2D_Pen3.csv"));

TEST(LogQuality, AccuracyRecoversAKnownOffsetFromKnownTargets) {
  // Five fixations of 1.5 s at 120 Hz with 0.3 s saccades between them. The left eye
  // looks 0.5 deg up-right of each target, the right eye 0.8 deg down-left, both with
  // 0.1 deg of Gaussian noise per axis; every 25th left sample is lost.
  test::TempDir d;
  const std::vector<FickAngles> targets = {{0, 0}, {12, 8}, {-12, 8}, {12, -8}, {-12, -8}};
  const double left_offset = 0.5, right_offset = 0.8;
  GazeLogHeader header;
  header.rate_hz = 120;
  auto w = GazeLogWriter::create(d.path("log.csv"), header);
  ASSERT_TRUE(w);
  std::mt19937 rng(21);
  std::normal_distribution<double> noise(0, 0.1);
  std::string targets_csv = "start_s,end_s,azimuth_deg,elevation_deg\n";
  std::int64_t i = 0;
  for (const FickAngles& t : targets) {
    targets_csv += std::to_string(static_cast<double>(i) / 120) + "," + std::to_string((static_cast<double>(i) + 180) / 120) +
                   "," + std::to_string(t.azimuth_deg) + "," + std::to_string(t.elevation_deg) + "\n";
    for (int k = 0; k < 180 + 36; ++k, ++i) {
      const bool fixating = k < 180;
      auto noisy = [&](const glm::dvec3& v) {
        const FickAngles a = fick_from_direction(v);
        return glm::vec3(direction_from_fick({a.azimuth_deg + noise(rng), a.elevation_deg + noise(rng)}));
      };
      GazeSample s;
      s.t_ns = i * 1'000'000'000 / 120;
      const FickAngles mid{t.azimuth_deg * (1 - (k - 180) / 36.0), t.elevation_deg};  // somewhere off target
      const FickAngles& look = fixating ? t : mid;
      s.eyes[0] = {kValidDirection, noisy(test::turned(look, left_offset, 45))};
      s.eyes[1] = {kValidDirection, noisy(test::turned(look, right_offset, 225))};
      if (i % 25 == 0) s.eyes[0] = {};
      ASSERT_TRUE(w->write(s));
    }
  }
  ASSERT_TRUE(w->commit());
  test::write_file(d.path("targets.csv"), targets_csv);

  const auto r = test::run(foveal_cli("log quality --json " + d.path("log.csv") + " --targets " + d.path("targets.csv")));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& acc = j["accuracy"];
  std::printf("recovered accuracy: left %.4f deg (true %.1f), right %.4f deg (true %.1f)\n",
              acc["left"]["offset_deg"].get<double>(), left_offset, acc["right"]["offset_deg"].get<double>(), right_offset);
  EXPECT_EQ(acc["left"]["targets"], 5);
  EXPECT_NEAR(acc["left"]["offset_deg"].get<double>(), left_offset, 0.05);
  EXPECT_NEAR(acc["right"]["offset_deg"].get<double>(), right_offset, 0.05);
  EXPECT_GT(acc["left"]["x_deg"].get<double>(), 0.3);   // up and to the right
  EXPECT_GT(acc["left"]["y_deg"].get<double>(), 0.3);
  EXPECT_LT(acc["right"]["x_deg"].get<double>(), -0.5);  // down and to the left
  EXPECT_LT(acc["right"]["y_deg"].get<double>(), -0.5);
  ASSERT_EQ(j["targets"].size(), 5u);
  for (const auto& t : j["targets"]) {
    EXPECT_NEAR(t["channels"]["left"]["offset_deg"].get<double>(), left_offset, 0.05) << t["where"];
    // Noise of 0.1 deg per axis: RMS-S2S about 0.1 * sqrt(2) * sqrt(2) = 0.2 deg.
    EXPECT_NEAR(t["channels"]["right"]["rms_s2s_deg"].get<double>(), 0.2, 0.03) << t["where"];
  }
  EXPECT_NEAR(j["channels"]["left"]["data_loss_pct"].get<double>(), 100.0 * 44 / 1080, 1e-4);  // 1 in 25 of 1080
  EXPECT_NEAR(j["channels"]["right"]["data_loss_pct"].get<double>(), 0.0, 1e-4);
}

TEST(LogQuality, BetweenMarkersMeasuresTheirWindow) {
  // 3 s at 120 Hz; markers at 1 s and 2 s (and a decoy 'end' before the start).
  test::TempDir d;
  GazeLogHeader header;
  header.rate_hz = 120;
  auto w = GazeLogWriter::create(d.path("m.csv"), header);
  ASSERT_TRUE(w);
  for (std::int64_t i = 0; i < 360; ++i) {
    const std::int64_t t = i * 1'000'000'000 / 120;
    const char* mark = i == 30 ? "end" : i == 120 ? "trial 1, start" : i == 240 ? "end" : nullptr;
    if (mark) {
      ASSERT_TRUE(w->mark({t, mark}));
    }
    GazeSample s;
    s.t_ns = t;
    s.eyes[0] = s.eyes[1] = {kValidDirection, {0, 0, -1}};
    ASSERT_TRUE(w->write(s));
  }
  ASSERT_TRUE(w->commit());
  const auto r = test::run(foveal_cli("log quality --json " + d.path("m.csv") + " --between 'trial 1, start' end"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["window"]["start_s"].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(j["window"]["end_s"].get<double>(), 2.0, 1e-9);
  EXPECT_EQ(j["channels"]["left"]["samples"], 120);

  const auto missing = test::run(foveal_cli("log quality " + d.path("m.csv") + " --between start end"));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find(d.path("m.csv") + ": quality: --between: no marker 'start' (markers: 'end', 'trial 1, start', 'end')"),
            std::string::npos) << missing.err;
  const auto backwards = test::run(foveal_cli("log quality " + d.path("m.csv") + " --between end 'trial 1, start'"));
  EXPECT_EQ(backwards.exit_code, 0) << backwards.err;  // the first 'end', then the next start
  const auto both = test::run(foveal_cli("log quality " + d.path("m.csv") + " --between a b --start 1"));
  EXPECT_EQ(both.exit_code, 2);
}

TEST(LogQuality, BadInputNamesTheFileAndLineAndExitsTwo) {
  test::TempDir d;
  const std::string log = d.path("log.csv");
  ASSERT_EQ(test::run(foveal_cli("synth --seed 3 --duration 2 --out " + log)).exit_code, 0);
  test::write_file(d.path("t.csv"), "start_s,end_s,azimuth_deg,elevation_deg\n0,1,0,0\n1,2,left,0\n");
  auto r = test::run(foveal_cli("log quality " + log + " --targets " + d.path("t.csv")));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(d.path("t.csv") + ":3: azimuth_deg: 'left' is not a finite number"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;

  r = test::run(foveal_cli("log quality " + log + " --start 5 --end 6"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(log + ": quality: the window [5.000, 2.000) s is empty"), std::string::npos) << r.err;

  test::write_file(d.path("bad.csv"), "# foveal-gaze-log v1\n");
  r = test::run(foveal_cli("log quality " + d.path("bad.csv")));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(d.path("bad.csv")), std::string::npos) << r.err;
}

}  // namespace
}  // namespace foveal
