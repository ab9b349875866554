// foveald's gaze-to-photon record end to end (docs/latency.md): a replay through the
// compositor, headless; every frame names a row of the replayed log, and its parts add
// up to its gaze-to-photon time.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

#include "csv_rows.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

// foveald's profile store and runtime folder in the test's own directory, so that no
// other test (or the machine's user) changes the profile it renders with.
std::string isolated(test::TempDir& dir) {
  return "XDG_CONFIG_HOME=" + dir.path("config") + " XDG_RUNTIME_DIR=" + dir.path("run") + " ";
}

std::set<std::string> log_times(const std::string& path) {
  std::set<std::string> t;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);)
    if (!line.empty() && line[0] != '#' && line.rfind("t_ns", 0) != 0) t.insert(line.substr(0, line.find(',')));
  return t;
}

TEST(FovealdLatency, EveryFrameNamesItsSampleAndItsPartsAddUp) {
  test::TempDir dir;
  const std::string log = test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv");
  for (const char* latch : {"late", "early"}) {
    const std::string out = dir.path(latch);
    const test::RunResult r = test::run(isolated(dir) + test::bin("foveald") + " --replay " + log +
                                        " --scene pattern:checker --size 320x180 --frames 30 --no-control --no-shm -q"
                                        " --latch " + latch + " --out " + out + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::ifstream csv(out + "/frames.csv");
    std::string header;
    ASSERT_TRUE(std::getline(csv, header));
    std::map<std::string, std::size_t> col;
    const auto names = test::csv_cells(header);
    for (std::size_t i = 0; i < names.size(); ++i) col[names[i]] = i;
    for (const char* name : {"sample_device_t_ns", "gaze_to_photon_ms", "tracker_to_host_ms", "host_to_latch_ms",
                             "latch_to_gpu_ms", "gpu_to_shown_ms", "shown_ns", "latch_ns", "frame_start_ns"})
      ASSERT_TRUE(col.count(name)) << name << " missing from " << header;
    const std::set<std::string> rows = log_times(log);
    int frames = 0;
    for (std::string line; std::getline(csv, line);) {
      const auto c = test::csv_cells(line);
      ASSERT_EQ(c.size(), names.size()) << line;
      if (c[col["gaze_to_photon_ms"]].empty()) continue;  // before the first sample
      ++frames;
      EXPECT_TRUE(rows.count(c[col["sample_device_t_ns"]])) << "frame " << c[0] << ": no log row at t_ns "
                                                            << c[col["sample_device_t_ns"]];
      const double total = std::stod(c[col["gaze_to_photon_ms"]]);
      double parts = 0;
      for (const char* p : {"tracker_to_host_ms", "host_to_latch_ms", "latch_to_gpu_ms", "gpu_to_shown_ms"}) {
        const double v = std::stod(c[col[p]]);
        EXPECT_GE(v, 0.0) << "frame " << c[0] << " " << p;
        parts += v;
      }
      EXPECT_GT(total, 0.0) << "frame " << c[0];
      EXPECT_NEAR(parts, total, 0.1) << "frame " << c[0];
      EXPECT_LE(std::stoll(c[col["frame_start_ns"]]), std::stoll(c[col["latch_ns"]])) << "frame " << c[0];
    }
    // Frames before the first sample (a loaded machine may render a few) have no record.
    EXPECT_GT(frames, 0) << latch;
    const nlohmann::json s = nlohmann::json::parse(test::read_file(out + "/summary.json"));
    const nlohmann::json& g = s["render"]["gaze_to_photon"];
    EXPECT_EQ(g["shown_clock"], "gpu_done");
    EXPECT_EQ(g["frames"], frames);
    EXPECT_GT(g["gaze_to_photon_ms"]["p99"].get<double>(), 0.0);
    EXPECT_EQ(s["render"]["latch"], latch);
    EXPECT_EQ(s["render"]["pacing"]["pacing"], "asap");
  }
}

// Frames of one sample show one fovea without prediction; with it, each frame's own
// display time moves it (the replay's eyes are seldom still). At a tenth of real time a
// sample lasts 83 ms, so even slow frames show each one several times, the first of them
// within the 50 ms the prediction reaches.
TEST(FovealdLatency, PredictionMovesTheFoveaToEachFramesDisplayTime) {
  test::TempDir dir;
  std::map<std::string, int> frames_of_a_sample_that_differ;
  for (const char* predict : {"on", "off"}) {
    const std::string out = dir.path(predict);
    const test::RunResult r = test::run(isolated(dir) + test::bin("foveald") + " --scene pattern:checker --size 160x90 --frames 80"
                                        " --speed 0.1 --no-control --no-shm -q --predict " + predict + " --out " + out);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::ifstream csv(out + "/frames.csv");
    std::string line;
    std::getline(csv, line);
    std::map<std::string, std::set<std::string>> fovea_of_sample;
    while (std::getline(csv, line)) {
      const auto c = test::csv_cells(line);
      fovea_of_sample[c[1]].insert(c[3] + "," + c[4]);
    }
    for (const auto& [t, foveae] : fovea_of_sample) frames_of_a_sample_that_differ[predict] += foveae.size() > 1;
    const nlohmann::json s = nlohmann::json::parse(test::read_file(out + "/summary.json"));
    EXPECT_EQ(s["render"]["prediction"], predict);
  }
  EXPECT_EQ(frames_of_a_sample_that_differ["off"], 0);
  EXPECT_GT(frames_of_a_sample_that_differ["on"], 0);
}

TEST(FovealdLatency, JitWithoutADisplayIsRefusedNamed) {
  test::TempDir dir;
  const test::RunResult r = test::run(isolated(dir) + test::bin("foveald") + " --scene pattern:checker --size 64x32 --frames 1 --no-control"
                                      " --no-shm --pacing jit --out " + dir.path("o"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--pacing jit needs a display"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir.path("o/frames.csv")));
}

}  // namespace
}  // namespace foveal
