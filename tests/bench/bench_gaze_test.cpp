// foveal bench --gaze and the methods without eye tracking, from the command line: a
// synthetic scanpath whose true gaze is known, a fovea lagged on purpose against one that
// is not, the latency model in the per-frame CSV, bad input (docs/bench.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "csv_rows.hpp"
#include "test_support.hpp"

using namespace foveal;

namespace {

using Row = test::CsvRow;
const auto read_csv = test::read_csv_rows;

const Row& find(const std::vector<Row>& rows, const std::string& method, const std::string& gaze) {
  static const Row none;
  for (const Row& r : rows)
    if (r.at("method") == method && r.at("gaze") == gaze) return r;
  ADD_FAILURE() << "no row " << method << "/" << gaze;
  return none;
}

double value(const Row& r, const std::string& key) { return r.count(key) ? std::stod(r.at(key)) : NAN; }

// A narrow display of 14 px/deg (±21.8°, 640×640 per eye): the synthetic scanpath's
// ±20° field fits, and the foveation weights fall off inside the view, so the metric
// can tell where the fovea is.
const char* kDisplay = R"({"format": "foveal-display-model v1", "name": "test_14ppd", "eye_width": 640, "eye_height": 640,
  "left":  {"tangents": {"left": -0.4, "right": 0.4, "bottom": -0.4, "top": 0.4}},
  "right": {"tangents": {"left": -0.4, "right": 0.4, "bottom": -0.4, "top": 0.4}}})";

struct GazeRun {
  std::vector<Row> rows, frames;
};

GazeRun bench(const test::TempDir& d, const std::string& name, const std::string& extra) {
  const std::string out = d.path(name);
  auto r = test::run(test::bin("foveal") + " bench --gaze " + d.path("g.csv") + " --display " + d.path("display.json") +
                     " --scene pattern:checker --methods rmfr,fixed,uniform --sigmas 3 --gaze-frames 16 --frames 1 --warmup 0"
                     " --no-png " + extra + " --out " + out);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return {read_csv(test::read_file(out + "/gaze.csv")), read_csv(test::read_file(out + "/gaze_frames.csv"))};
}

}  // namespace

TEST(BenchGaze, ALaggedFoveaScoresWorseThanAnExactOneAtTheTrueGaze) {
  test::TempDir d;
  // No noise, blinks or pursuits: the raw log is the true gaze, fixations of 150-600 ms
  // between saccades of 2-20 degrees.
  ASSERT_EQ(test::run(test::bin("foveal") + " synth --seed 11 --duration 8 --noise 0 --blink-rate 0 --pursuit 0 --out " +
                      d.path("g.csv")).exit_code, 0);
  test::write_file(d.path("display.json"), kDisplay);
  // The G-buffer pipeline, which this test was written against: on this 14 px/deg checker
  // the visibility pipeline's periphery is filtered to grey and its fovea blends every tile
  // edge once more than full does (docs/results/pattern_seams.md), so its patch
  // PSNR is low both on time and late and does not tell the lag.
  const GazeRun exact = bench(d, "exact", "--latency-ms 0 --pipeline gbuffer");
  const GazeRun lagged = bench(d, "lagged", "--latency-ms 400 --pipeline gbuffer");
  ASSERT_EQ(exact.rows.size(), 4u);  // the oracle, rmfr, fixed, uniform at one level
  ASSERT_EQ(lagged.rows.size(), 4u);

  const Row& on_time = find(exact.rows, "rmfr", "filtered");
  const Row& late = find(lagged.rows, "rmfr", "filtered");
  EXPECT_EQ(value(on_time, "frames"), 16);
  EXPECT_EQ(value(on_time, "blink_frames"), 0);
  // With the fovea on the gaze the filtered fovea is within a degree of it; 400 ms late it
  // is where the eye was before the last saccade, more often than not.
  EXPECT_LT(value(on_time, "fovea_error_deg_mean"), 1.0);
  EXPECT_GT(value(late, "fovea_error_deg_mean"), 3.0);
  EXPECT_GT(value(on_time, "fpsnr_mean"), value(late, "fpsnr_mean") + 0.1);
  EXPECT_GT(value(on_time, "patch_psnr_mean"), value(late, "patch_psnr_mean") + 2.0);
  EXPECT_LT(value(on_time, "patch_exceed_share"), value(late, "patch_exceed_share"));
  EXPECT_GE(value(late, "patch_exceed_share"), 0.3);
  // Perfect tracking is the bound; it does not move with the latency of the filtered fovea
  // beyond which frames the truth is read at.
  const Row& oracle = find(lagged.rows, "rmfr", "true");
  EXPECT_NEAR(value(oracle, "fovea_error_deg_mean"), 0.0, 1e-3);
  EXPECT_EQ(value(oracle, "patch_exceed_share"), 0.0);
  EXPECT_GT(value(oracle, "fpsnr_mean"), value(late, "fpsnr_mean"));
  // Every method shades the same samples at a level.
  for (const Row& r : exact.rows) EXPECT_EQ(r.at("shaded_samples"), on_time.at("shaded_samples")) << r.at("method");

  // JOD per frame, each eye at its true gaze (docs/bench.md, "JOD"): after the old columns,
  // within (0, 10], both eyes' figure between the two; gaze.csv's mean, p5 and min of them.
  for (const GazeRun* run : {&exact, &lagged}) {
    for (const Row& f : run->frames) {
      ASSERT_TRUE(f.count("jod_left") && f.count("jod_right") && f.count("jod"));
      for (const char* k : {"jod_left", "jod_right", "jod"}) {
        EXPECT_GT(value(f, k), 0) << k;
        EXPECT_LE(value(f, k), 10) << k;
      }
      EXPECT_GE(value(f, "jod"), std::min(value(f, "jod_left"), value(f, "jod_right")) - 1e-5);
      EXPECT_LE(value(f, "jod"), std::max(value(f, "jod_left"), value(f, "jod_right")) + 1e-5);
    }
    for (const Row& r : run->rows) {
      double sum = 0, n = 0;
      for (const Row& f : run->frames)
        if (f.at("method") == r.at("method") && f.at("gaze") == r.at("gaze")) sum += value(f, "jod"), ++n;
      ASSERT_EQ(n, 16) << r.at("method");
      EXPECT_NEAR(value(r, "jod_mean"), sum / n, 1e-4) << r.at("method");
      EXPECT_LE(value(r, "jod_min"), value(r, "jod_p5"));
      EXPECT_LE(value(r, "jod_p5"), value(r, "jod_mean"));
    }
  }

  // The latency model: display = frame start + latency, the fovea from a sample no later
  // than the frame start; fixed and uniform at the optical centre whatever the gaze.
  ASSERT_EQ(lagged.frames.size(), 64u);
  for (const Row& f : lagged.frames) {
    EXPECT_NEAR(value(f, "t_display_s") - value(f, "t_render_s"), 0.4, 1e-6);
    EXPECT_LE(value(f, "t_sample_s"), value(f, "t_render_s") + 1e-9);
    if (f.at("gaze") == "none") {
      EXPECT_DOUBLE_EQ(value(f, "fovea_l_x"), 0.5);
      EXPECT_DOUBLE_EQ(value(f, "fovea_r_y"), 0.5);
    }
  }
}

TEST(BenchGaze, SpreadPicksOneFramePerEccentricityBand) {
  test::TempDir d;
  ASSERT_EQ(test::run(test::bin("foveal") + " synth --seed 11 --duration 8 --noise 0 --blink-rate 0 --pursuit 0 --out " +
                      d.path("g.csv")).exit_code, 0);
  test::write_file(d.path("display.json"), kDisplay);
  auto run = [&](const std::string& name, const std::string& pick) {
    const std::string out = d.path(name);
    auto r = test::run(test::bin("foveal") + " bench --gaze " + d.path("g.csv") + " --display " + d.path("display.json") +
                       " --scene pattern:noise --methods rmfr --sigmas 2 --size 64x32 --frames 1 --warmup 0 --no-png --no-jod"
                       " --latency-ms 0 --gaze-frames 4 " + pick + " --out " + out);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<Row> frames;
    for (const Row& f : read_csv(test::read_file(out + "/gaze_frames.csv")))
      if (f.at("gaze") == "filtered") frames.push_back(f);
    return frames;
  };
  // The eccentricity from the optical centre, computed here from the true gaze points
  // through the test display's symmetric frustum (tangents ±0.4), both eyes' mean.
  auto ecc = [](const Row& f) {
    double sum = 0;
    for (const char* e : {"l", "r"}) {
      const double tx = -0.4 + 0.8 * value(f, std::string("true_") + e + "_x"), ty = -0.4 + 0.8 * value(f, std::string("true_") + e + "_y");
      sum += std::atan(std::sqrt(tx * tx + ty * ty)) * 180 / M_PI;
    }
    return sum / 2;
  };
  const auto spread = run("spread", "--gaze-pick spread --gaze-spread-max 16");
  ASSERT_GE(spread.size(), 3u);  // the scanpath reaches at least three of the four 4-degree bands
  std::set<int> bands;
  for (std::size_t i = 0; i < spread.size(); ++i) {
    EXPECT_NEAR(value(spread[i], "true_ecc_deg"), ecc(spread[i]), 0.05);
    EXPECT_LE(value(spread[i], "true_ecc_deg"), 16.0);
    EXPECT_TRUE(bands.insert(static_cast<int>(value(spread[i], "true_ecc_deg") / 4)).second) << "two frames in one band";
    if (i) {
      EXPECT_LT(std::stoi(spread[i - 1].at("frame")), std::stoi(spread[i].at("frame")));  // in stream order
    }
  }
  // The default keeps its frames: every (stream / N)-th, eccentricities as they come.
  const auto even = run("even", "");
  ASSERT_EQ(even.size(), 4u);
  EXPECT_EQ(even[0].at("frame"), "0");
  EXPECT_NEAR(value(even[1], "true_ecc_deg"), ecc(even[1]), 0.05);
}

TEST(BenchGaze, BadInputExitsTwoNamingTheProblemAndWritesNothing) {
  test::TempDir d;
  const std::string base = test::bin("foveal") + " bench --scene pattern:noise --methods rmfr --sigmas 2 --size 64x32 --no-png";
  auto missing = test::run(base + " --gaze " + d.path("nope.csv") + " --out " + d.path("a"));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("nope.csv"), std::string::npos) << missing.err;
  EXPECT_FALSE(std::filesystem::exists(d.path("a/gaze.csv")));

  ASSERT_EQ(test::run(test::bin("foveal") + " synth --seed 1 --duration 2 --out " + d.path("g.csv")).exit_code, 0);
  auto head = test::run(base + " --gaze " + d.path("g.csv") + " --head recorded --out " + d.path("b"));
  EXPECT_EQ(head.exit_code, 2);
  EXPECT_NE(head.err.find("carries no head pose"), std::string::npos) << head.err;
  auto short_log = test::run(base + " --gaze " + d.path("g.csv") + " --gaze-start 5 --out " + d.path("c"));
  EXPECT_EQ(short_log.exit_code, 2);
  EXPECT_NE(short_log.err.find("too short"), std::string::npos) << short_log.err;
  auto alone = test::run(base + " --gaze " + d.path("g.csv") + " --rotation --out " + d.path("e"));
  EXPECT_EQ(alone.exit_code, 2);
  EXPECT_NE(alone.err.find("--gaze runs on its own"), std::string::npos) << alone.err;
  auto without = test::run(base + " --display hires_3800_35ppd --out " + d.path("f"));
  EXPECT_NE(without.exit_code, 0);
  EXPECT_NE(without.err.find("--gaze"), std::string::npos) << without.err;
  for (const char* dir : {"b", "c", "e", "f"}) EXPECT_FALSE(std::filesystem::exists(d.path(std::string(dir) + "/gaze.csv"))) << dir;
}

TEST(BaselinesCli, FixedAndUniformIgnoreTheGazeAndShadeRmfrsSamples) {
  test::TempDir d;
  auto render = [&](const std::string& method) {
    auto r = test::run(test::bin("foveal") + " render --scene pattern:checker --size 160x90 --frames 1 --method " + method +
                       " --fovea-left 0.1,0.2 --fovea-right 0.9,0.8 --json --out " + d.path(method + ".png"));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const auto rmfr = render("rmfr"), fixed = render("fixed"), uniform = render("uniform");
  for (const char* eye : {"left", "right"}) {
    EXPECT_EQ(fixed["eyes"][eye]["fovea"], nlohmann::json({0.5, 0.5})) << eye;  // the Vive's optical centre
    EXPECT_EQ(uniform["eyes"][eye]["fovea"], nlohmann::json({0.5, 0.5})) << eye;
    EXPECT_EQ(fixed["eyes"][eye]["shaded_samples"], rmfr["eyes"][eye]["shaded_samples"]) << eye;
    EXPECT_EQ(uniform["eyes"][eye]["shaded_samples"], rmfr["eyes"][eye]["shaded_samples"]) << eye;
  }
  EXPECT_NEAR(rmfr["eyes"]["left"]["fovea"][0].get<double>(), 0.1, 1e-9);
  // foveald renders them from its live fovea and reports the fovea each frame used.
  auto daemon = test::run("XDG_CONFIG_HOME=" + d.path("cfg") + " " + test::bin("foveald") +
                          " --speed 1 --frames 3 --size 64x36 --scene pattern:checker --method fixed --no-control --no-shm -q --out " +
                          d.path("daemon"));
  ASSERT_EQ(daemon.exit_code, 0) << daemon.err;
  const auto frames = read_csv(test::read_file(d.path("daemon/frames.csv")));
  ASSERT_EQ(frames.size(), 3u);
  for (const Row& f : frames)
    for (const char* k : {"fovea_left_x", "fovea_left_y", "fovea_right_x", "fovea_right_y"}) EXPECT_DOUBLE_EQ(value(f, k), 0.5) << k;
  auto bad = test::run(test::bin("foveal") + " render --method fovea --out " + d.path("x.png"));
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("uniform"), std::string::npos) << bad.err;  // the list of methods names them
}
