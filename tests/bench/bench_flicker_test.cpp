// foveal bench --flicker from the command line (real EGL rendering): the gaze filter
// lowers RMFR's flicker under gaze jitter; a moving camera changes the reference's frames
// and both pipelines get their figures against it; temporal accumulation's rows; --blend-at;
// bad input (docs/stability.md).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include <nlohmann/json.hpp>

#include "csv_rows.hpp"
#include "test_support.hpp"

using namespace foveal;

namespace {

using Row = test::CsvRow;
const auto read_csv = test::read_csv_rows;

// The row of pipeline × camera × method × gaze (an empty row and a failure when missing).
const Row& find(const std::vector<Row>& rows, const std::string& pipeline, const std::string& camera, const std::string& method,
                const std::string& gaze) {
  static const Row none;
  for (const Row& r : rows)
    if (r.at("pipeline") == pipeline && r.at("camera") == camera && r.at("method") == method && r.at("gaze") == gaze) return r;
  ADD_FAILURE() << "no row " << pipeline << "/" << camera << "/" << method << "/" << gaze;
  return none;
}

double value(const Row& r, const std::string& key) { return r.count(key) && !r.at(key).empty() ? std::stod(r.at(key)) : NAN; }

// foveal bench --flicker of RMFR on WaterBottle framed to fill the view, 4 frames at
// 192×108, the fovea fixed, through both pipelines, into d/b; `options` adds the rest.
test::RunResult run_moving_camera(const test::TempDir& d, const std::string& options) {
  const std::string scene = test::source_path("data/scenes/WaterBottle/WaterBottle.gltf");
  return test::run(test::bin("foveal") + " bench --scene " + scene + " --methods rmfr --sigmas 2 --size 192x108 --frames 1 --warmup 0 "
                   "--flicker --flicker-frames 4 --grid-sigma 2 --camera-fill --flicker-gaze fixed --flicker-pipelines gbuffer,visibility "
                   "--no-png " + options + " --out " + d.path("b"));
}

TEST(BenchFlicker, RmfrFlickersLessWithTheGazeFilter) {
  test::TempDir d;
  auto r = test::run(test::bin("foveal") + " bench --scene pattern:noise --methods rmfr --sigmas 2 --size 320x180 --frames 1 "
                     "--flicker --flicker-frames 24 --grid-sigma 2.6 --no-png --out " + d.path("b"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = read_csv(test::read_file(d.path("b/flicker.csv")));
  ASSERT_EQ(rows.size(), 4u);  // full and rmfr × raw and filtered; the still camera and the default (visibility) pipeline
  const double raw = value(find(rows, "visibility", "static", "rmfr", "raw"), "flicker");
  const double filtered = value(find(rows, "visibility", "static", "rmfr", "filtered"), "flicker");
  EXPECT_GT(raw, 0.0);
  EXPECT_LT(filtered, raw);
  EXPECT_EQ(value(find(rows, "visibility", "static", "full", "raw"), "flicker"), 0.0);  // a static scene at full rate does not flicker
  // JOD as a video along the path, each eye at its recorded gaze: full's frames are the
  // reference's (10), and the filter's steadier fovea looks better than the raw gaze's.
  for (const char* gaze : {"raw", "filtered"}) EXPECT_EQ(value(find(rows, "visibility", "static", "full", gaze), "jod"), 10) << gaze;
  const Row& raw_row = find(rows, "visibility", "static", "rmfr", "raw");
  EXPECT_GT(value(find(rows, "visibility", "static", "rmfr", "filtered"), "jod"), value(raw_row, "jod"));
  EXPECT_LT(value(raw_row, "jod"), 10);
  EXPECT_GT(value(raw_row, "jod_left"), 0);
  EXPECT_GT(value(raw_row, "jod_right"), 0);
  for (const Row& row : rows) {
    // A still camera: the reference never changes, so flicker is the frames' own change.
    EXPECT_EQ(value(row, "reference_change"), 0.0);
    EXPECT_EQ(row.at("flicker"), row.at("periphery_change"));
  }
  EXPECT_NE(test::read_file(d.path("b/bench.csv")).find("rmfr,2,"), std::string::npos);
}

TEST(BenchFlicker, AMovingCameraChangesTheFramesAndBothPipelinesAreScored) {
  test::TempDir d;
  auto r = run_moving_camera(d, "--flicker-sigma-nd 3 --camera-path static,orbit:600 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = read_csv(test::read_file(d.path("b/flicker.csv")));
  EXPECT_EQ(rows.size(), 8u);  // 2 cameras × 2 pipelines × (full, rmfr) × fixed gaze
  for (const char* pipeline : {"gbuffer", "visibility"})
    for (const char* method : {"full", "rmfr"}) {
      // Still camera and fixed fovea: nothing moves, nothing changes.
      const Row& still = find(rows, pipeline, "static", method, "fixed");
      EXPECT_EQ(value(still, "periphery_change"), 0.0) << pipeline << " " << method;
      EXPECT_EQ(value(still, "flicker"), 0.0) << pipeline << " " << method;
      // The orbit moves the reference and the frames; each pipeline gets its figure.
      const Row& orbit = find(rows, pipeline, "orbit:600", method, "fixed");
      EXPECT_GT(value(orbit, "reference_change"), 0.5) << pipeline << " " << method;
      EXPECT_GT(value(orbit, "periphery_change"), 0.5) << pipeline << " " << method;
      EXPECT_EQ(value(orbit, "sigma_nd"), std::string(method) == "full" ? 1.0 : 3.0);
      const double flicker = value(orbit, "flicker");
      EXPECT_TRUE(std::isfinite(flicker) && flicker >= 0) << pipeline << " " << method;
      // Only RMFR has a prefiltered reference (image-space RMFR of the reference).
      const double pre = value(orbit, "prefiltered_flicker");
      if (std::string(method) == "rmfr") EXPECT_TRUE(std::isfinite(pre) && pre > 0) << pipeline;
      else EXPECT_TRUE(std::isnan(pre)) << pipeline;
    }
  // The reference is full through the G-buffer pipeline: its own row has no flicker; the
  // foveated frames, which differ from it, do.
  EXPECT_EQ(value(find(rows, "gbuffer", "orbit:600", "full", "fixed"), "flicker"), 0.0);
  EXPECT_GT(value(find(rows, "gbuffer", "orbit:600", "rmfr", "fixed"), "flicker"), 0.0);
  EXPECT_GT(value(find(rows, "visibility", "orbit:600", "rmfr", "fixed"), "flicker"), 0.0);
  for (const Row& row : rows) EXPECT_EQ(row.at("reference"), "gbuffer");  // --flicker-reference shared, the default
  // --json lists the same rows.
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["flicker"].size(), 8u);
  EXPECT_EQ(j["flicker"][0]["camera"], "static");
  EXPECT_TRUE(j["flicker"][0]["prefiltered_flicker"].is_null());  // full
}

TEST(BenchFlicker, OwnReferenceScoresEachPipelineAgainstItsOwnFullFrames) {
  test::TempDir d;
  auto r = run_moving_camera(d, "--camera-path orbit:600 --flicker-reference own");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = read_csv(test::read_file(d.path("b/flicker.csv")));
  ASSERT_EQ(rows.size(), 4u);
  for (const char* pipeline : {"gbuffer", "visibility"}) {
    // Each pipeline's full frames are its reference: their row has no flicker at all.
    const Row& full = find(rows, pipeline, "orbit:600", "full", "fixed");
    EXPECT_EQ(full.at("reference"), pipeline);
    EXPECT_EQ(value(full, "flicker"), 0.0) << pipeline;
    EXPECT_EQ(value(full, "periphery_error"), 0.0) << pipeline;
    EXPECT_GT(value(find(rows, pipeline, "orbit:600", "rmfr", "fixed"), "flicker"), 0.0) << pipeline;
  }
}

TEST(BenchFlicker, TemporalOnAddsARowWhereAccumulationApplies) {
  test::TempDir d;
  auto r = run_moving_camera(d, "--temporal on,off --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = read_csv(test::read_file(d.path("b/flicker.csv")));
  // Per pipeline full (off), rmfr off; rmfr on only in the visibility pipeline (RMFR's
  // kernel there is what accumulates).
  ASSERT_EQ(rows.size(), 5u);
  std::map<std::string, int> seen;
  for (const Row& row : rows) ++seen[row.at("pipeline") + "/" + row.at("method") + "/" + row.at("temporal")];
  EXPECT_EQ(seen, (std::map<std::string, int>{{"gbuffer/full/off", 1}, {"gbuffer/rmfr/off", 1}, {"visibility/full/off", 1},
                                              {"visibility/rmfr/off", 1}, {"visibility/rmfr/on", 1}}));
  // Still camera and fovea: without accumulation every frame is the same; with it the
  // grid is jittered frame to frame, so the frames change while the history fills.
  for (const Row& row : rows) {
    if (row.at("method") != "rmfr" || row.at("pipeline") != "visibility") continue;
    if (row.at("temporal") == "off") EXPECT_EQ(value(row, "periphery_change"), 0.0);
    else EXPECT_GT(value(row, "periphery_change"), 0.0);
  }
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["flicker"].size(), 5u);
  EXPECT_EQ(j["flicker"][4]["temporal"], "on");  // off first, whatever the order given
}

// --blend-at reaches the flicker bench's foveated frames: on Dungeon with the three panes of
// tools/scenes/blend_panes.py, RMFR's frames through the visibility pipeline differ between
// the panes shaded at output and at the kept samples, and full (the reference) does not.
TEST(BenchFlicker, BlendAtChoosesWhereTheFoveatedFramesShadeTheirPanes) {
  test::TempDir d;
  ASSERT_EQ(test::run("/usr/bin/python3 " + test::source_path("tools/scenes/blend_panes.py") + " " +
                      test::source_path("data/scenes/Dungeon/dungeon_simplified.gltf") + " " + d.path("panes")).exit_code, 0);
  std::map<std::string, std::vector<Row>> rows;
  for (const std::string at : {"output", "samples"}) {
    auto r = test::run(test::bin("foveal") + " bench --scene " + d.path("panes/dungeon_simplified_panes.gltf") +
                       " --methods rmfr --sigmas 3 --size 192x108 --frames 1 --warmup 0 --flicker --flicker-frames 2 --grid-sigma 3"
                       " --flicker-gaze fixed --flicker-pipelines visibility --camera-path static --no-jod --no-png --blend-at " + at +
                       " --out " + d.path(at));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    rows[at] = read_csv(test::read_file(d.path(at + "/flicker.csv")));
  }
  const Row& full_output = find(rows["output"], "visibility", "static", "full", "fixed");
  const Row& full_samples = find(rows["samples"], "visibility", "static", "full", "fixed");
  EXPECT_EQ(full_output.at("periphery_error"), full_samples.at("periphery_error"));
  const double output = value(find(rows["output"], "visibility", "static", "rmfr", "fixed"), "periphery_error");
  const double samples = value(find(rows["samples"], "visibility", "static", "rmfr", "fixed"), "periphery_error");
  EXPECT_GT(std::abs(output - samples), 1e-3) << "output " << output << ", samples " << samples;
}

TEST(BenchFlicker, BadInputExitsTwoNamingTheOptionAndWritesNothing) {
  test::TempDir d;
  const std::string base = test::bin("foveal") + " bench --scene pattern:noise --methods rmfr --sigmas 2 --size 64x36 --frames 1 ";
  auto expect_bad = [&](const std::string& args, const std::string& message) {
    auto r = test::run(base + args + " --no-png --out " + d.path("b"));
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find(message), std::string::npos) << args << ": " << r.err;
    EXPECT_FALSE(std::filesystem::exists(d.path("b/flicker.csv"))) << args;
  };
  expect_bad("--flicker --camera-path spin", "--camera-path: 'spin'");
  expect_bad("--flicker --camera-path orbit:-2", "--camera-path: 'orbit:-2': the speed '-2'");
  expect_bad("--flicker --flicker-gaze raw,sideways", "--flicker-gaze: 'sideways'");
  expect_bad("--flicker --flicker-pipelines gbuffer,gbuffer", "--flicker-pipelines: 'gbuffer' is listed twice");
  expect_bad("--flicker --camera-pivot 0", "--camera-pivot");
  expect_bad("--flicker --flicker-sigma-nd 0.5", "--flicker-sigma-nd");
  expect_bad("--flicker --flicker-reference mine", "--flicker-reference");
  expect_bad("--camera-path orbit", "--camera-path requires --flicker");
  expect_bad("--flicker --temporal sideways", "--temporal: 'sideways': expected off or on");
  expect_bad("--flicker --temporal on,on", "--temporal: 'on' is listed twice");
  expect_bad("--temporal on", "--temporal on: temporal accumulation needs a sequence of frames");
  // A log without head poses cannot drive the recorded camera.
  ASSERT_EQ(test::run(test::bin("foveal") + " synth --seed 3 --duration 3 --out " + d.path("g.csv")).exit_code, 0);
  expect_bad("--flicker --flicker-frames 3 --camera-path recorded --flicker-log " + d.path("g.csv"), d.path("g.csv") + " has no head pose");
}

}  // namespace
