// JOD in foveal bench (docs/bench.md, "JOD"): the stereo scorer each eye alone at its own
// fixation, and the bench.csv/bench.json columns from the command line, with --no-jod.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <random>

#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "csv_rows.hpp"
#include "foveal/bench/bench_jod.hpp"
#include "foveal/core/gaze_log.hpp"
#include "test_support.hpp"

using namespace foveal;

namespace {

const char* kHeader =
    "scene,method,sigma,shaded_samples,cost,gpu_ms,cpu_ms,shadow_ms,gbuffer_ms,mapping_ms,lighting_ms,inverse_ms,psnr_db,ssim,fpsnr_db";

image::Image grey_noise(int w, int h, unsigned seed) {
  image::Image img(w, h);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> v(60, 190);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.at(x, y);
      p[0] = p[1] = p[2] = static_cast<std::uint8_t>(v(rng));
      p[3] = 255;
    }
  return img;
}

// The same noise added at the same place of both eyes' images (x0 of each eye's width).
image::Image damaged(const image::Image& ref, double x0, int eye_w) {
  image::Image out = ref;
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> d(-40, 40);
  const int r = eye_w / 20;
  for (int e = 0; e < 2; ++e)
    for (int y = ref.height / 2 - r; y < ref.height / 2 + r; ++y)
      for (int x = static_cast<int>(x0 * eye_w) - r; x < static_cast<int>(x0 * eye_w) + r; ++x)
        for (int c = 0; c < 3; ++c) {
          std::uint8_t& p = out.at(e * eye_w + x, y)[c];
          p = static_cast<std::uint8_t>(std::clamp(p + d(rng), 0, 255));
        }
  return out;
}

double cell(const test::CsvRow& r, const std::string& k) { return r.count(k) ? std::stod(r.at(k)) : NAN; }

std::string first_line(const std::string& text) { return text.substr(0, text.find('\n')); }

}  // namespace

TEST(BenchJod, EachEyeIsScoredAloneAtItsOwnFixation) {
  const int w = 1440, h = 800;  // the Vive's field of view at half its pixels: 6.6 ppd
  auto scorer = bench::StereoJodScorer::create(DisplayModel::vive_pro_eye(), w, h, 1);
  ASSERT_TRUE(scorer) << scorer.error().message;
  const image::Image ref = grey_noise(w, h, 3);
  auto same = scorer->still(ref, ref, std::array<double, 2>{0.5, 0.5}, std::nullopt);
  ASSERT_TRUE(same) << same.error().message;
  EXPECT_DOUBLE_EQ(same->left, 10);
  EXPECT_DOUBLE_EQ(same->right, 10);
  EXPECT_DOUBLE_EQ(same->combined, 10);

  // Damage at x = 0.15 of both eyes: the left eye looks at it, the right one far away.
  const image::Image test = damaged(ref, 0.15, w / 2);
  const bench::EyeFovea on = std::array<double, 2>{0.15, 0.5}, off = std::array<double, 2>{0.85, 0.5};
  auto s = scorer->still(ref, test, on, off);
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_LT(s->left, s->right - 0.05);
  EXPECT_GT(s->combined, s->left);
  EXPECT_LT(s->combined, s->right);
  // Swapped foveae swap which eye sees the damage (the Vive's eyes differ a little in
  // their geometry, so the figures are not exchanged exactly).
  auto swapped = scorer->still(ref, test, off, on);
  ASSERT_TRUE(swapped);
  EXPECT_LT(swapped->right, swapped->left - 0.05);
  EXPECT_NEAR(swapped->right, s->left, 0.05);
  EXPECT_EQ(scorer->scored(), 3);
  EXPECT_DOUBLE_EQ(scorer->photometry().peak_cd_m2, 133.3);  // metrics --jod's defaults
  EXPECT_DOUBLE_EQ(scorer->photometry().black_cd_m2, 0.1);

  auto wrong = scorer->still(ref, image::Image(w, h + 2), on, on);
  ASSERT_FALSE(wrong);
  EXPECT_NE(wrong.error().message.find("made for 1440x800"), std::string::npos) << wrong.error().message;
  EXPECT_FALSE(bench::StereoJodScorer::create(DisplayModel::vive_pro_eye(), 255, 128));
}

TEST(BenchJod, VideoOfIdenticalFramesScoresTenAndDamageScoresLower) {
  const int w = 512, h = 256;
  auto scorer = bench::StereoJodScorer::create(DisplayModel::vive_pro_eye(), w, h, 1);
  ASSERT_TRUE(scorer);
  auto same = scorer->video(90), hurt = scorer->video(90);
  ASSERT_TRUE(same && hurt);
  for (unsigned k = 0; k < 4; ++k) {
    const image::Image ref = grey_noise(w, h, k);
    const bench::EyeFovea c = std::array<double, 2>{0.5, 0.5};
    ASSERT_TRUE(same->push(ref, ref, c, c));
    ASSERT_TRUE(hurt->push(ref, k % 2 ? damaged(ref, 0.5, w / 2) : ref, c, c));  // flicker at the fovea
  }
  auto a = same->score(), b = hurt->score();
  ASSERT_TRUE(a && b);
  EXPECT_DOUBLE_EQ(a->combined, 10);
  EXPECT_LT(b->combined, a->combined - 0.03);
  EXPECT_EQ(scorer->scored(), 8);
}

TEST(BenchJod, BenchWritesJodPerEyeAfterTheOldColumnsAndNoJodLeavesThemOut) {
  test::TempDir d;
  const std::string common = test::bin("foveal") + " bench --scene pattern:checker --methods rmfr,uniform --sigmas 1.4,4"
                             " --size 320x180 --frames 1 --warmup 0 --no-png --out ";
  auto r = test::run(common + d.path("jod"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("JOD added"), std::string::npos) << r.err;  // its cost per frame
  const std::string csv = test::read_file(d.path("jod/bench.csv"));
  EXPECT_EQ(first_line(csv), std::string(kHeader) + ",blend_ms,jod_left,jod_right,jod");
  const auto rows = test::read_csv_rows(csv);
  ASSERT_EQ(rows.size(), 5u);  // full, then each method at two levels
  EXPECT_EQ(rows[0].at("method"), "full");
  for (const char* k : {"jod_left", "jod_right", "jod"}) EXPECT_EQ(cell(rows[0], k), 10) << k;
  for (const auto& row : rows)
    for (const char* k : {"jod_left", "jod_right", "jod"}) {
      EXPECT_GT(cell(row, k), 0) << k;
      EXPECT_LE(cell(row, k), 10) << k;
    }
  auto at = [&](const std::string& m, const std::string& sigma) {
    for (const auto& row : rows)
      if (row.at("method") == m && row.at("sigma") == sigma) return row;
    ADD_FAILURE() << m << " " << sigma;
    return test::CsvRow{};
  };
  for (const char* m : {"rmfr", "uniform"}) {
    EXPECT_GE(cell(at(m, "1.4"), "jod"), cell(at(m, "4"), "jod")) << m;  // fewer samples never look better
    EXPECT_LT(cell(at(m, "4"), "jod"), 10) << m;
  }
  const auto j = nlohmann::json::parse(test::read_file(d.path("jod/bench.json")));
  EXPECT_EQ(j["jod"]["peak_cd_m2"], 133.3);
  EXPECT_EQ(j["jod"]["black_cd_m2"], 0.1);
  EXPECT_EQ(j["jod"]["frames"], 5);
  EXPECT_GT(j["jod"]["ppd"][0].get<double>(), 0);
  EXPECT_EQ(j["rows"][0]["jod"], 10);
  EXPECT_TRUE(j["rows"][1].contains("jod_left") && j["rows"][1].contains("jod_right") && j["rows"][1].contains("jod_ms"));

  r = test::run(common + d.path("none") + " --no-jod");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err.find("JOD"), std::string::npos) << r.err;
  const std::string plain = test::read_file(d.path("none/bench.csv"));
  EXPECT_EQ(first_line(plain), std::string(kHeader) + ",blend_ms");
  EXPECT_FALSE(nlohmann::json::parse(test::read_file(d.path("none/bench.json"))).contains("jod"));
}

TEST(BenchJod, GazeBenchAppendsJodColumnsAndNoJodLeavesThemOut) {
  test::TempDir d;
  ASSERT_EQ(test::run(test::bin("foveal") + " synth --seed 2 --duration 3 --out " + d.path("g.csv")).exit_code, 0);
  const std::string common = test::bin("foveal") + " bench --gaze " + d.path("g.csv") +
                             " --scene pattern:noise --methods rmfr,uniform --sigmas 2 --size 128x64 --gaze-frames 2 --frames 1"
                             " --warmup 0 --no-png --out ";
  auto r = test::run(common + d.path("jod"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("bench --gaze: JOD added"), std::string::npos) << r.err;
  auto header = [&](const std::string& file) { return first_line(test::read_file(d.path(file))); };
  const std::string summary = header("jod/gaze.csv"), frames = header("jod/gaze_frames.csv");
  EXPECT_TRUE(summary.ends_with(",fovea_error_deg_mean,jod_mean,jod_p5,jod_min")) << summary;
  EXPECT_TRUE(frames.ends_with(",patch_psnr_db,exceeds,jod_left,jod_right,jod,true_ecc_deg")) << frames;
  const auto j = nlohmann::json::parse(test::read_file(d.path("jod/gaze.json")));
  EXPECT_EQ(j["jod"]["frames"], 2 * 3);  // two frames × the oracle, rmfr and uniform
  EXPECT_TRUE(j["rows"][0].contains("jod_mean"));

  r = test::run(common + d.path("none") + " --no-jod");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(header("none/gaze.csv") + ",jod_mean,jod_p5,jod_min", summary);
  const std::string plain = header("none/gaze_frames.csv");  // true_ecc_deg stays last
  ASSERT_TRUE(plain.ends_with(",exceeds,true_ecc_deg")) << plain;
  EXPECT_EQ(plain.substr(0, plain.size() - 13) + ",jod_left,jod_right,jod,true_ecc_deg", frames);
  EXPECT_FALSE(nlohmann::json::parse(test::read_file(d.path("none/gaze.json"))).contains("jod"));
}

TEST(BenchJod, FlickerAppendsVideoJodColumnsAndNoJodLeavesThemOut) {
  test::TempDir d;
  const std::string common = test::bin("foveal") + " bench --scene pattern:noise --methods rmfr --sigmas 2 --size 64x36 --frames 1"
                             " --warmup 0 --flicker --flicker-frames 3 --flicker-gaze fixed --no-png --out ";
  auto r = test::run(common + d.path("jod"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run(common + d.path("none") + " --no-jod");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto header = [&](const std::string& file) { return first_line(test::read_file(d.path(file))); };
  EXPECT_EQ(header("jod/flicker.csv"), header("none/flicker.csv") + ",jod_left,jod_right,jod");
  EXPECT_TRUE(header("none/flicker.csv").ends_with(",prefiltered_flicker,reference,temporal"));
  const auto rows = test::read_csv_rows(test::read_file(d.path("jod/flicker.csv")));
  ASSERT_EQ(rows.size(), 2u);  // full and rmfr
  EXPECT_EQ(rows[0].at("jod"), "10");
  const auto j = nlohmann::json::parse(test::read_file(d.path("jod/bench.json")));
  EXPECT_NEAR(j["flicker"][1]["jod"].get<double>(), std::stod(rows[1].at("jod")), 1e-4);  // the CSV has 6 digits
}

TEST(BenchJod, ThePanelsLuminanceReachesTheMetricAndNonsenseIsRefused) {
  const int w = 256, h = 128;
  const image::Image ref = grey_noise(w, h, 5), test = damaged(ref, 0.5, w / 2);
  const bench::EyeFovea c = std::array<double, 2>{0.5, 0.5};
  auto vive = bench::StereoJodScorer::create(DisplayModel::vive_pro_eye(), w, h, 1);
  auto bright = bench::StereoJodScorer::create(DisplayModel::vive_pro_eye(), w, h, 1, perception::Photometry{1000, 0.5});
  ASSERT_TRUE(vive && bright);
  EXPECT_DOUBLE_EQ(bright->photometry().peak_cd_m2, 1000);
  EXPECT_DOUBLE_EQ(bright->photometry().black_cd_m2, 0.5);
  auto a = vive->still(ref, test, c, c), b = bright->still(ref, test, c, c);
  ASSERT_TRUE(a && b);
  EXPECT_GT(std::abs(a->combined - b->combined), 0.01) << "a brighter panel shows the same damage differently";
  for (const perception::Photometry& bad : {perception::Photometry{100, 100}, perception::Photometry{100, 200},
                                             perception::Photometry{0, -1}, perception::Photometry{NAN, 0.1},
                                             perception::Photometry{INFINITY, 0.1}}) {
    auto s = bench::StereoJodScorer::create(DisplayModel::vive_pro_eye(), w, h, 1, bad);
    ASSERT_FALSE(s) << bad.peak_cd_m2 << " " << bad.black_cd_m2;
    EXPECT_NE(s.error().message.find("JOD: display luminance"), std::string::npos) << s.error().message;
  }
}

TEST(BenchJod, BenchTakesPeakAndBlackAndRefusesNonsense) {
  test::TempDir d;
  const std::string common = test::bin("foveal") + " bench --scene pattern:checker --methods uniform --sigmas 3"
                             " --size 128x64 --frames 1 --warmup 0 --no-png --out ";
  auto r = test::run(common + d.path("default"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run(common + d.path("dim") + " --peak 10 --black 0.01");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(test::read_file(d.path("dim/bench.json")));
  EXPECT_EQ(j["jod"]["peak_cd_m2"], 10);
  EXPECT_EQ(j["jod"]["black_cd_m2"], 0.01);
  const auto def = nlohmann::json::parse(test::read_file(d.path("default/bench.json")));
  EXPECT_EQ(def["jod"]["peak_cd_m2"], 133.3);  // perception::Photometry{}'s, unchanged
  EXPECT_EQ(def["jod"]["black_cd_m2"], 0.1);
  ASSERT_EQ(j["rows"].size(), 2u);
  // A dim panel hides some of the loss (7.46 against 7.31 at 128x64).
  EXPECT_GT(j["rows"][1]["jod"].get<double>(), def["rows"][1]["jod"].get<double>() + 0.05) << "the row was scored on the dim panel";
  for (const char* bad : {"--peak 100 --black 100", "--peak 100 --black 200", "--peak 0", "--peak -5 --black -6", "--peak nan",
                          "--black inf", "--black 0"}) {
    SCOPED_TRACE(bad);
    r = test::run(common + d.path("bad") + " " + bad);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("--peak"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(d.path("bad")));
  }
  // --gaze scores with the same panel and records it in gaze.json.
  ASSERT_EQ(test::run(test::bin("foveal") + " synth --seed 2 --duration 3 --out " + d.path("g.csv")).exit_code, 0);
  r = test::run(test::bin("foveal") + " bench --gaze " + d.path("g.csv") + " --scene pattern:noise --methods uniform --sigmas 2"
                " --size 64x36 --gaze-frames 1 --frames 1 --warmup 0 --no-png --peak 10 --black 0.01 --out " + d.path("gaze"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto g = nlohmann::json::parse(test::read_file(d.path("gaze/gaze.json")));
  EXPECT_EQ(g["jod"]["peak_cd_m2"], 10);
  EXPECT_EQ(g["jod"]["black_cd_m2"], 0.01);
}

TEST(BenchJod, ExperimentsAppendJodColumnsScoredAtTheirFoveaAndNoJodLeavesThemOut) {
  test::TempDir d;
  const std::string common = test::bin("foveal") + " bench --scene pattern:checker --methods rmfr,uniform --sigmas 3 --size 128x72"
                             " --frames 1 --warmup 0 --f-grid --grid-values 0.2,0.3 --rotation --stability --no-png --out ";
  auto r = test::run(common + d.path("jod"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run(common + d.path("none") + " --no-jod");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::size_t scored = 0;
  for (const char* table : {"bench.csv", "fgrid.csv", "rotation.csv", "stability.csv"}) {
    SCOPED_TRACE(table);
    const std::string with = test::read_file(d.path(std::string("jod/") + table)), without = test::read_file(d.path(std::string("none/") + table));
    EXPECT_EQ(first_line(with), first_line(without) + ",jod_left,jod_right,jod");
    const auto rows = test::read_csv_rows(with);
    ASSERT_FALSE(rows.empty());
    scored += rows.size();
    for (const auto& row : rows)
      for (const char* k : {"jod_left", "jod_right", "jod"}) {
        EXPECT_GT(cell(row, k), 0) << k;
        EXPECT_LE(cell(row, k), 10) << k;
      }
    // The other columns are those of the run without JOD, row for row.
    const auto plain = test::read_csv_rows(without);
    ASSERT_EQ(plain.size(), rows.size());
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (const auto& [k, v] : plain[i])
        if (!k.ends_with("_ms")) {
          EXPECT_EQ(rows[i].at(k), v) << k << " row " << i;
        }
  }
  const auto j = nlohmann::json::parse(test::read_file(d.path("jod/bench.json")));
  EXPECT_EQ(j["jod"]["frames"].get<std::size_t>(), scored) << "one JOD score per row of every table";
  // Rotated stripes at σ 3 lose detail in the fovea: every method below 10 at some angle.
  const auto rotation = test::read_csv_rows(test::read_file(d.path("jod/rotation.csv")));
  EXPECT_TRUE(std::any_of(rotation.begin(), rotation.end(), [](const test::CsvRow& row) { return cell(row, "jod") < 9.9; }));
  // Stability: the metric looks where the fovea is. Uniform resolution ignores the fovea,
  // so its frame is the same at every position and only the fixation moves: its JOD rises
  // as the fixation leaves the centre for the border, where the pattern's loss is further
  // out in the periphery (7.738 to 7.778 along the diagonal at 128x72).
  const auto stability = test::read_csv_rows(test::read_file(d.path("jod/stability.csv")));
  std::map<std::string, double> uniform;
  for (const auto& row : stability)
    if (row.at("method") == "uniform") uniform[row.at("path") + " " + row.at("t")] = cell(row, "jod");
  ASSERT_EQ(uniform.size(), 22u);
  EXPECT_GT(uniform["diagonal 1"], uniform["diagonal 0"] + 0.02);
  EXPECT_GT(uniform["vertical 1"], uniform["vertical 0"] + 0.02);
}

namespace {

// The head's mean speed over `n` frames of the stream from `start_s` as the timeline sees
// it, computed here from the log itself: each frame takes the pose of the latest sample
// no later than its start.
double log_head_speed(const std::vector<GazeSample>& log, double start_s, int n, double fps) {
  const TimeNs first = log.front().t_ns + static_cast<TimeNs>(std::llround(start_s * 1e9));
  std::vector<glm::dquat> q;
  for (int k = 0; k < n; ++k) {
    const TimeNs t = first + static_cast<TimeNs>(std::llround(k * 1e9 / fps));
    const GazeSample* latest = nullptr;
    for (const GazeSample& s : log)
      if (s.t_ns <= t && s.head.valid) latest = &s;
    q.push_back(glm::dquat(latest->head.pose.orientation));
  }
  double deg = 0;
  for (std::size_t k = 1; k < q.size(); ++k) deg += glm::degrees(glm::angle(glm::conjugate(q[k - 1]) * q[k]));
  return deg / ((n - 1) / fps);
}

}  // namespace

TEST(BenchJod, GazeVideoScoresEachLogMethodAndLevelAsOneVideoAlongTheHead) {
  test::TempDir d;
  const std::string log = test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv");  // a v2 log: the head turns at 3.6-3.7 s
  const std::string common = test::bin("foveal") + " bench --gaze " + log + " --gaze-start 3.6 --scene " +
                             test::source_path("data/scenes/WaterBottle/WaterBottle.gltf") +
                             " --methods uniform,rmfr --sigmas 1 --size 96x54 --gaze-frames 1 --frames 1 --warmup 0 --no-png";
  auto r = test::run(common + " --gaze-video 8 --out " + d.path("rec"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  r = test::run(common + " --gaze-video 8 --head static --out " + d.path("static"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string csv = test::read_file(d.path("rec/gaze_video.csv"));
  EXPECT_EQ(first_line(csv), "scene,log,display,method,gaze,sigma_d,sigma_nd,frames,blink_frames,fps,head_speed_deg_s,jod_left,jod_right,jod,"
                             "temporal,shaded_samples,cost,gpu_ms,cpu_ms,saccades,post_saccade_frames,post_saccade_fpsnr_mean,"
                             "post_saccade_jod_mean,post_saccade_fpsnr_worst_vs_off,post_saccade_jod_worst_vs_off");
  const auto rows = test::read_csv_rows(csv), still = test::read_csv_rows(test::read_file(d.path("static/gaze_video.csv")));
  ASSERT_EQ(rows.size(), 3u);  // the oracle, uniform, rmfr at the one level
  ASSERT_EQ(still.size(), 3u);
  auto samples = read_gaze_log(log);
  ASSERT_TRUE(samples) << samples.error().message;
  const double speed = log_head_speed(*samples, 3.6, 8, 90);
  EXPECT_GT(speed, 5);  // deg/s: a real turn
  for (std::size_t i = 0; i < rows.size(); ++i) {
    SCOPED_TRACE(rows[i].at("method") + " " + rows[i].at("gaze"));
    EXPECT_EQ(cell(rows[i], "frames") + cell(rows[i], "blink_frames"), 8);
    EXPECT_EQ(rows[i].at("fps"), "90");
    EXPECT_NEAR(cell(rows[i], "head_speed_deg_s"), speed, 1e-3 * speed);
    EXPECT_EQ(cell(still[i], "head_speed_deg_s"), 0);
    for (const char* k : {"jod_left", "jod_right", "jod"}) {
      EXPECT_GT(cell(rows[i], k), 0) << k;
      EXPECT_LE(cell(rows[i], k), 10) << k;
    }
  }
  // Uniform at σ_d 1: the dominant (right) eye renders full, so each of its frames equals
  // that frame's reference, rendered on the same head pose: a video JOD of 10 exactly.
  const auto& uniform = rows[1];
  ASSERT_EQ(uniform.at("method"), "uniform");
  EXPECT_EQ(cell(uniform, "jod_right"), 10);
  EXPECT_LT(cell(uniform, "jod_left"), 10);  // σ_nd 1.5
  const auto j = nlohmann::json::parse(test::read_file(d.path("rec/gaze.json")));
  EXPECT_EQ(j["video_frames"], 8);
  ASSERT_EQ(j["video"].size(), 3u);
  EXPECT_NEAR(j["video"][1]["jod"].get<double>(), cell(uniform, "jod"), 1e-4);
  EXPECT_EQ(j["logs"][0]["video_frames"], 8);

  // Without --gaze-video, no table; --gaze-video needs JOD and --gaze.
  r = test::run(common + " --out " + d.path("none"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(std::filesystem::exists(d.path("none/gaze_video.csv")));
  r = test::run(common + " --gaze-video 4 --no-jod --out " + d.path("bad"));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--gaze-video"), std::string::npos) << r.err;
  r = test::run(test::bin("foveal") + " bench --scene pattern:noise --gaze-video 4 --out " + d.path("bad"));
  EXPECT_NE(r.exit_code, 0);
  EXPECT_FALSE(std::filesystem::exists(d.path("bad")));
}

TEST(BenchJod, GazeVideoWithTemporalAccumulationAtEqualSamplesAndAfterSaccades) {
  test::TempDir d;
  // TESTNA01's right eye jumps about 3 deg a frame at 2.74-2.77 s: a real saccade in the
  // video's 12 frames from 2.7 s.
  const std::string log = test::source_path("data/gaze/vive_pro_eye_TESTNA01.csv");
  auto r = test::run(test::bin("foveal") + " bench --gaze " + log + " --gaze-start 2.7 --scene " +
                     test::source_path("data/scenes/WaterBottle/WaterBottle.gltf") +
                     " --methods rmfr,kfr --sigmas 2 --size 96x54 --gaze-frames 1 --frames 1 --warmup 0 --no-png --gaze-video 12"
                     " --temporal on,off --out " + d.path("b"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = test::read_csv_rows(test::read_file(d.path("b/gaze_video.csv")));
  const auto frames = test::read_csv_rows(test::read_file(d.path("b/gaze_video_frames.csv")));
  // The oracle and rmfr off and on (RMFR's kernel accumulates), kfr off only.
  ASSERT_EQ(rows.size(), 5u);
  std::map<std::string, const test::CsvRow*> by;
  for (const auto& row : rows) by[row.at("method") + "/" + row.at("gaze") + "/" + row.at("temporal")] = &row;
  ASSERT_EQ(by.size(), 5u);
  for (const char* k : {"rmfr/true/off", "rmfr/true/on", "rmfr/filtered/off", "rmfr/filtered/on", "kfr/filtered/off"})
    EXPECT_TRUE(by.count(k)) << k;
  const auto& off = *by["rmfr/filtered/off"];
  const auto& on = *by["rmfr/filtered/on"];
  // Equal shaded samples: the jitter moves the grid, not its size.
  EXPECT_EQ(off.at("shaded_samples"), on.at("shaded_samples"));
  EXPECT_GT(cell(on, "cost"), 0);
  EXPECT_LT(cell(on, "cost"), 1);
  EXPECT_NE(cell(off, "jod"), cell(on, "jod")) << "the switch reaches the frames";
  std::map<std::string, int> post;  // post-saccade frames per point, from the frames file
  for (const auto& f : frames) {
    const std::string point = f.at("method") + "/" + f.at("gaze") + "/" + f.at("temporal");
    const bool after = f.at("post_saccade") == "1";
    post[point] += after ? 1 : 0;
    EXPECT_EQ(!f.at("jod").empty(), after) << point << " frame " << f.at("frame") << ": JOD on the frames after saccades only";
    EXPECT_GT(cell(f, "fpsnr_db"), 0);
  }
  EXPECT_EQ(frames.size(), 5u * 12u);
  for (const auto& [point, row] : by) {
    SCOPED_TRACE(point);
    EXPECT_GE(cell(*row, "saccades"), 1);
    EXPECT_EQ(cell(*row, "post_saccade_frames"), post[point]);
    EXPECT_GT(post[point], 0);
    EXPECT_GT(cell(*row, "post_saccade_jod_mean"), 0);
    // Against the same frames without accumulation: on rows only.
    EXPECT_EQ(row->at("post_saccade_jod_worst_vs_off").empty(), row->at("temporal") == "off");
    EXPECT_EQ(row->at("post_saccade_fpsnr_worst_vs_off").empty(), row->at("temporal") == "off");
  }
  const auto j = nlohmann::json::parse(test::read_file(d.path("b/gaze.json")));
  EXPECT_EQ(j["temporal"], "off,on");
  EXPECT_EQ(j["pipeline"], "visibility");
  EXPECT_EQ(j["blend_at"], "output");
  EXPECT_GT(j["temporal_history_mb"].get<double>(), 0);
}

TEST(BenchJod, GazeVideoLeavesOutTheFramesInBlinksAsTheStillsDo) {
  test::TempDir d;
  ASSERT_EQ(test::run(test::bin("foveal") + " synth --seed 5 --duration 4 --blink-rate 2 --out " + d.path("g.csv")).exit_code, 0);
  // At 30 Hz the stream from 1 s has about 90 frames: --gaze-frames 1000 scores every one
  // of them as stills, --gaze-video 1000 all of them as one video.
  auto r = test::run(test::bin("foveal") + " bench --gaze " + d.path("g.csv") + " --gaze-fps 30 --scene pattern:noise --methods uniform"
                     " --sigmas 2 --size 64x36 --gaze-frames 1000 --gaze-video 1000 --frames 1 --warmup 0 --no-png --out " + d.path("b"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto video = test::read_csv_rows(test::read_file(d.path("b/gaze_video.csv")));
  const auto stills = test::read_csv_rows(test::read_file(d.path("b/gaze.csv")));
  ASSERT_EQ(video.size(), 2u);
  ASSERT_EQ(stills.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_GT(cell(video[i], "blink_frames"), 0);
    EXPECT_EQ(video[i].at("blink_frames"), stills[i].at("blink_frames"));
    EXPECT_EQ(video[i].at("frames"), stills[i].at("frames"));
    EXPECT_EQ(video[i].at("fps"), "30");
    EXPECT_EQ(cell(video[i], "head_speed_deg_s"), 0);  // a log without head poses
  }
}
