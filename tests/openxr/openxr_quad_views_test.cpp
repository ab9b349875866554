// Quad views for OpenXR apps (issue 37): an app that renders the Dungeon into four views
// (examples/openxr_quad_views) through EGL on Monado's null compositor, which offers only
// stereo, with foveal's layer in between and foveald serving gaze (or not).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>

#include "foveal/image/image.hpp"
#include "foveal/runtime/fovea_prediction.hpp"
#include "foveal/runtime/inset_levels.hpp"
#include "quad_views_fixture.hpp"

namespace foveal {
namespace {

using nlohmann::json;
using test::OpenXRRig;
using test::kLayerShare;
using test::kQuad;
using test::QuadViews;
using test::Tan;
using test::tangents;

TEST_F(QuadViews, TheLayerOffersQuadViewsOnAStereoRuntimeAndNotWhenItIsOff) {
  const auto on = run_app({"--frames", "2", "--stereo"}, "on");
  const auto off = run_app({"--frames", "2", "--stereo"}, "off", {"FOVEAL_OPENXR_DISABLE=1"});
  const json s_on = event(on, "system"), s_off = event(off, "system");
  ASSERT_TRUE(s_on.contains("view_configurations")) << rig_.err("on");
  ASSERT_TRUE(s_off.contains("view_configurations")) << rig_.err("off");
  auto lists = [](const json& s, int c) {
    const auto& v = s["view_configurations"];
    return std::find(v.begin(), v.end(), c) != v.end();
  };
  EXPECT_TRUE(lists(s_on, kQuad)) << s_on.dump();
  EXPECT_TRUE(s_on["quad_views_extension"].get<bool>());
  EXPECT_FALSE(lists(s_off, kQuad)) << "Monado itself offers no quad views: " << s_off.dump();
  EXPECT_FALSE(s_off["quad_views_extension"].get<bool>());
  // Stereo stays first: an app that takes the first configuration it knows is not moved.
  EXPECT_EQ(s_on["view_configurations"][0], s_off["view_configurations"][0]);
}

TEST_F(QuadViews, WithFovealdEveryFrameObeysTheRulesAndTheInnerViewsFollowTheGaze) {
  const test::RunResult synth = test::run(test::bin("foveal") + " synth --seed 11 --duration 40 --noise 0.2 --blink-rate 0.5 -o " +
                                          rig_.path("synth.csv") + " --truth " + rig_.path("truth.csv"));
  ASSERT_EQ(synth.exit_code, 0) << synth.err;
  const auto stereo = run_app({"--frames", "2", "--stereo"}, "stereo");
  const json stereo_sizes = event(stereo, "views")["sizes"];
  ASSERT_EQ(stereo_sizes.size(), 2u) << rig_.err("stereo");

  auto fd = rig_.foveald({"--source", "replay:" + rig_.path("synth.csv"), "--no-render", "--out", rig_.path("fd")}, "foveald");
  wait_for_block();
  const auto lines = run_app({"--frames", "120", "--gaze"}, "quad");
  fd->signal(SIGTERM);
  ASSERT_EQ(fd->wait(30000), 0) << rig_.err("foveald");

  const json sys = event(lines, "system"), views = event(lines, "views");
  EXPECT_EQ(sys.value("supportsFoveatedRendering", -1), 1) << sys.dump();
  ASSERT_EQ(views.value("configuration", ""), "quad") << rig_.err("quad");
  EXPECT_TRUE(views["foveated"].get<bool>());
  // Sizes from the default profile (EFR): right eye dominant at σ_d 2, left at σ_nd 3;
  // the inner views at full density over 0.35 of the view.
  const json& sz = views["sizes"];
  const double sigma[2] = {3.0, 2.0};
  for (int e = 0; e < 2; ++e) {
    const double w = stereo_sizes[e][0].get<double>(), h = stereo_sizes[e][1].get<double>();
    EXPECT_EQ(sz[e][0].get<int>(), std::lround(w / sigma[e])) << "outer width, eye " << e;
    EXPECT_EQ(sz[e][1].get<int>(), std::lround(h / sigma[e])) << "outer height, eye " << e;
    EXPECT_EQ(sz[e + 2][0].get<int>(), std::lround(w * 0.35)) << "inner width, eye " << e;
    EXPECT_EQ(sz[e + 2][1].get<int>(), std::lround(h * 0.35)) << "inner height, eye " << e;
  }

  // The specification's rules, every frame.
  const auto fs = frames(lines);
  ASSERT_GE(fs.size(), 120u) << rig_.err("quad");
  for (const json& f : fs) {
    ASSERT_EQ(f["views"].size(), 4u);
    for (int e = 0; e < 2; ++e) {
      EXPECT_EQ(f["views"][e]["q"], f["views"][e + 2]["q"]) << "views " << e << " and " << e + 2 << " share a pose";
      EXPECT_EQ(f["views"][e]["p"], f["views"][e + 2]["p"]);
      const Tan o = tangents(f["views"][e]), i = tangents(f["views"][e + 2]);
      EXPECT_TRUE(i.l > o.l && i.r < o.r && i.d > o.d && i.u < o.u) << "inner view " << e + 2 << " leaves its outer view: " << f.dump();
    }
  }

  // The inner views' centres against the scanpath's truth, per eye, in settled fixations.
  // The app reads the gaze too (--gaze), so the layer places its inner views on the sample
  // the app's action state latched, whose time the app prints: each frame is judged
  // against the truth at that sample's time, however late a loaded machine ran foveald
  // or the app.
  using Truth = test::TruthRow;
  const std::vector<Truth> truth = test::read_truth(rig_.path("truth.csv"), rig_.path("fd"));
  auto truth_at = [&](TimeNs t) -> const Truth* {
    const Truth* best = nullptr;
    for (const Truth& x : truth)
      if (x.t <= t) best = &x;
    return best;
  };
  auto tracked = [](const json& f) {
    return f.contains("gaze") && f["gaze"]["active"].get<bool>() && f["gaze"]["tracked"].get<bool>();
  };
  int settled = 0, within = 0, clamped = 0;
  double worst = 0;
  for (std::size_t k = 0; k < fs.size(); ++k) {
    const json& f = fs[k];
    if (!tracked(f)) continue;
    // Settled: the sample lies 150 ms or more into its fixation (the filter has caught
    // up after the saccade), and the gaze was tracked in every frame of the last 200 ms
    // of display time and the one before them (after a blink the inset eases back from
    // the fixed place over 150 ms of display time, by design).
    const TimeNs sample = f["gaze"]["sample_ns"].get<TimeNs>();
    const Truth* now = truth_at(sample);
    const Truth* before = truth_at(sample - 150 * kNsPerMs);
    if (!now || !before || now->event != "fixation" || before->event != "fixation" || now->index != before->index) continue;
    const TimeNs display = f["display_ns"].get<TimeNs>();
    bool steady = true;
    for (std::size_t j = k; j-- > 0 && steady;) {
      steady = tracked(fs[j]);
      if (fs[j]["display_ns"].get<TimeNs>() < display - 200 * kNsPerMs) break;
    }
    if (!steady) continue;
    for (int e = 0; e < 2; ++e) {
      const Tan o = tangents(f["views"][e]), i = tangents(f["views"][e + 2]);
      // An inset pushed in from an edge is centred beside the gaze, by design.
      if (i.l - o.l < 2e-3 * (o.r - o.l) || o.r - i.r < 2e-3 * (o.r - o.l) || i.d - o.d < 2e-3 * (o.u - o.d) ||
          o.u - i.u < 2e-3 * (o.u - o.d)) {
        ++clamped;
        continue;
      }
      const glm::vec3 centre(static_cast<float>(i.cx()), static_cast<float>(i.cy()), -1.0f);
      const double err = test::angle_deg(centre, now->dir[e]);
      ++settled;
      within += err <= 1.0;
      worst = std::max(worst, err);
    }
  }
  std::printf("quad views: %zu frames, %d settled eye-frames (%d within 1 deg of the truth, worst %.3f deg), %d at an edge\n",
              fs.size(), settled, within, worst, clamped);
  ASSERT_GT(settled, 10) << "too few settled fixations seen";
  EXPECT_EQ(within, settled) << "inner views more than 1 deg from the gaze; worst " << worst << " deg";
  EXPECT_LT(frames_at_the_fixed_place(fs), static_cast<int>(fs.size()) / 2) << "the inset did not follow the gaze";
}

TEST_F(QuadViews, InnerViewsArePlacedOnTheGazePredictedToTheDisplayTime) {
  // Issue 37 item 1: in smooth pursuit each inner view's centre is closer to the eye's
  // true gaze at the time it was predicted to than the sample it was predicted from is.
  // That time is the frame's displayTime, or the sample's time plus the 50 ms horizon where
  // the display is further ahead (a loaded machine): judged there, the figure does not
  // depend on how late the app's frame is.
  const test::RunResult synth = test::run(test::bin("foveal") + " synth --seed 5 --duration 40 --noise 0.1 --blink-rate 0.1 " +
                                          "--pursuit 0.7 -o " + rig_.path("synth.csv") + " --truth " + rig_.path("truth.csv"));
  ASSERT_EQ(synth.exit_code, 0) << synth.err;
  auto fd = rig_.foveald({"--source", "replay:" + rig_.path("synth.csv"), "--no-render", "--out", rig_.path("fd")}, "foveald");
  wait_for_block();
  const auto lines = run_app({"--frames", "120", "--gaze"}, "quad");
  fd->signal(SIGTERM);
  ASSERT_EQ(fd->wait(30000), 0) << rig_.err("foveald");
  const auto rows = test::read_trace(rig_.path("fd"), DisplayModel::vive_pro_eye());
  const std::vector<test::TruthRow> truth = test::read_truth(rig_.path("truth.csv"), rig_.path("fd"));
  // Eye e's true direction at t, between two rows of one pursuit; nullopt elsewhere.
  auto pursuit_at = [&](TimeNs t, int e) -> std::optional<glm::vec3> {
    auto after = std::upper_bound(truth.begin(), truth.end(), t, [](TimeNs x, const test::TruthRow& r) { return x < r.t; });
    if (after == truth.begin() || after == truth.end()) return std::nullopt;
    const test::TruthRow &a = *(after - 1), &b = *after;
    if (a.event != "pursuit" || b.event != "pursuit" || a.index != b.index || b.t <= a.t) return std::nullopt;
    const float u = static_cast<float>(t - a.t) / static_cast<float>(b.t - a.t);
    return glm::normalize(a.dir[e] * (1.0f - u) + b.dir[e] * u);
  };
  std::vector<double> placed, sampled;
  const auto fs = frames(lines);
  for (std::size_t k = 0; k < fs.size(); ++k) {
    const json& f = fs[k];
    if (!f.contains("gaze") || !f["gaze"]["active"].get<bool>() || !f["gaze"]["tracked"].get<bool>()) continue;
    const TimeNs sample = f["gaze"]["sample_ns"].get<TimeNs>(), display = f["display_ns"].get<TimeNs>();
    // The inset eases over 150 ms after a loss: only frames with tracked gaze for 200 ms before.
    bool steady = true;
    for (std::size_t j = k; j-- > 0 && steady;) {
      steady = fs[j].contains("gaze") && fs[j]["gaze"]["active"].get<bool>() && fs[j]["gaze"]["tracked"].get<bool>();
      if (fs[j]["display_ns"].get<TimeNs>() < display - 200 * kNsPerMs) break;
    }
    const test::TraceRow* row = nullptr;
    for (const auto& r : rows)
      if (std::llabs(r.t_ns - sample) <= 2 * kNsPerMs) row = &r;
    if (!steady || !row || display <= sample) continue;
    for (int e = 0; e < 2; ++e) {
      const TimeNs target = std::min<TimeNs>(display, sample + FoveaPrediction{}.max_horizon_ns);
      const auto at_display = pursuit_at(target, e), into = pursuit_at(sample - 50 * kNsPerMs, e);
      if (!at_display || !into || !row->tracked[e]) continue;
      const Tan o = tangents(f["views"][e]), i = tangents(f["views"][e + 2]);
      if (i.l - o.l < 2e-3 * (o.r - o.l) || o.r - i.r < 2e-3 * (o.r - o.l) || i.d - o.d < 2e-3 * (o.u - o.d) ||
          o.u - i.u < 2e-3 * (o.u - o.d))
        continue;  // pushed in from an edge: centred beside the gaze, by design
      const glm::vec3 centre(static_cast<float>(i.cx()), static_cast<float>(i.cy()), -1.0f);
      placed.push_back(test::angle_deg(centre, *at_display));
      sampled.push_back(test::angle_deg(row->dir[e], *at_display));
    }
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  std::printf("quad views in pursuit: %zu eye-frames; against the truth at the predicted time the inner view's centre is %.3f deg "
              "off (median), the sample it came from %.3f deg\n",
              placed.size(), median(placed), median(sampled));
  ASSERT_GT(placed.size(), 20u) << "too few pursuit frames: " << rig_.err("quad");
  EXPECT_LT(median(placed), 0.5 * median(sampled)) << "inner views not placed on the gaze predicted to displayTime";
}

TEST_F(QuadViews, WithoutFovealdTheAppRunsOnWithTheFixedInset) {
  const auto lines = run_app({"--frames", "8"}, "quad");
  const json sys = event(lines, "system");
  EXPECT_EQ(sys.value("supportsFoveatedRendering", -1), 0) << "no gaze: " << sys.dump();
  const auto fs = frames(lines);
  ASSERT_EQ(fs.size(), 8u) << rig_.err("quad");
  EXPECT_EQ(frames_at_the_fixed_place(fs), 8);
  EXPECT_NE(event(lines, "end").value("frames", 0), 0);
}

TEST_F(QuadViews, FovealdStoppingMidRunSendsTheInsetBackToTheFixedPlaceWithoutAJump) {
  // One fixation off the centre (10° right, 5° up): the gaze never moves, so every step
  // of the inset after the stop is the ease. A scanpath's saccade in the last samples
  // before the stop reached frames drawn after it on a loaded machine and was judged as
  // the ease (0.139 in one 200 ms step against a distance of 0.129).
  ASSERT_NO_FATAL_FAILURE(test::write_fixation_log(rig_.path("fixation.csv"), 30, 0.17632698, 0.08748866));
  auto fd = rig_.foveald({"--source", "replay:" + rig_.path("fixation.csv"), "--no-render", "--out", rig_.path("fd")}, "foveald");
  wait_for_block();
  // Without prediction: until the layer sees foveald gone, its last sample would be
  // extrapolated along its velocity (up to 50 ms, by design), moving the inset a little
  // before the ease begins; this test is about the ease alone.
  // 180 frames: however long a loaded machine takes foveald to exit, frames enough remain
  // after it for the 150 ms ease.
  auto app = rig_.quad_app({"--frames", "180"}, {"FOVEAL_OPENXR_PREDICT=off"}, "quad", kLayerShare);
  // Stop foveald once the inset has followed the gaze for 5 frames (its ease from the
  // fixed place at the start is over), then let the app go on.
  auto following = [&] {
    const auto fs = frames(rig_.lines("quad"));
    if (fs.size() < 10) return false;
    const std::vector<json> last(fs.end() - 5, fs.end());
    return frames_at_the_fixed_place(last) == 0;
  };
  for (int i = 0; i < 30000 && !following(); ++i) sleep_until_ns(monotonic_now_ns() + 10 * kNsPerMs);
  ASSERT_TRUE(following()) << rig_.err("quad");
  fd->signal(SIGTERM);
  ASSERT_EQ(fd->wait(30000), 0) << rig_.err("foveald");
  const std::size_t stopped_at = frames(rig_.lines("quad")).size();
  ASSERT_EQ(app->wait(300000), 0) << rig_.err("quad");
  const auto fs = frames(rig_.lines("quad"));
  ASSERT_EQ(fs.size(), 180u);
  // After the stop the inset eases to the fixed place over 150 ms of display time: no
  // step between two frames is larger than the smoothstep allows for the display time
  // between them (at most 1.5 times the linear share), however far apart a loaded
  // machine puts the frames.
  const double from = tangents(fs[stopped_at - 1]["views"][3]).cx();
  const double to = tangents(fs.back()["views"][1]).cx();
  const double distance = std::abs(to - from);
  int worse = 0;
  for (std::size_t k = stopped_at; k < fs.size(); ++k) {
    const double step = std::abs(tangents(fs[k]["views"][3]).cx() - tangents(fs[k - 1]["views"][3]).cx());
    const double dt_ms = static_cast<double>(fs[k]["display_ns"].get<TimeNs>() - fs[k - 1]["display_ns"].get<TimeNs>()) / 1e6;
    const double allowed = distance * std::min(1.0, 1.5 * dt_ms / 150.0) + 1e-4;
    if (step > allowed) {
      ++worse;
      ADD_FAILURE() << "frame " << k << ": the inset moved " << step << " in " << dt_ms << " ms (at most " << allowed << ")";
    }
  }
  EXPECT_EQ(frames_at_the_fixed_place({fs.back()}), 1) << "the inset is not back at the fixed place";
  EXPECT_GT(distance, 0.0) << "the inset was at the fixed place before the stop: the gaze never moved it";
  EXPECT_EQ(worse, 0);
}

/// The two eyes' images side by side, as the layer's capture lays them out.
image::Image side_by_side(const image::Image& l, const image::Image& r) {
  image::Image out(l.width + r.width, std::max(l.height, r.height));
  for (int y = 0; y < l.height; ++y) std::copy(l.at(0, y), l.at(0, y) + l.width * 4, out.at(0, y));
  for (int y = 0; y < r.height; ++y) std::copy(r.at(0, y), r.at(0, y) + r.width * 4, out.at(l.width, y));
  return out;
}

/// The pixels of eye e's output that lie inside its inner view by more than the blend
/// band (3 degrees) and a pixel: there the composed image is the inner view's alone.
image::Rect inside_inner(const json& frame, int e, int eye_w, int h) {
  const Tan o = tangents(frame["views"][e]), i = tangents(frame["views"][e + 2]);
  const double band = 3.0 * M_PI / 180.0;
  auto px_x = [&](double t) { return (t - o.l) / (o.r - o.l) * eye_w; };
  auto px_y = [&](double t) { return (o.u - t) / (o.u - o.d) * h; };  // top row first
  const int x0 = static_cast<int>(std::ceil(px_x(std::tan(std::atan(i.l) + band)))) + 1;
  const int x1 = static_cast<int>(std::floor(px_x(std::tan(std::atan(i.r) - band)))) - 1;
  const int y0 = static_cast<int>(std::ceil(px_y(std::tan(std::atan(i.u) - band)))) + 1;
  const int y1 = static_cast<int>(std::floor(px_y(std::tan(std::atan(i.d) + band)))) - 1;
  return {x0 + e * eye_w, y0, x1 - x0, y1 - y0};
}

TEST_F(QuadViews, TheComposedImageMatchesItsGoldenAndIsTheFullDensityFrameInsideTheInnerViews) {
  // Quad views without foveation (their fixed inset, at the sizes for it) and --still
  // draw every run alike: a golden frame.
  std::filesystem::create_directories(rig_.path("capture"));
  std::filesystem::create_directories(rig_.path("full"));
  const auto quad = run_app({"--frames", "6", "--still", "--no-foveated"}, "quad",
                            {"FOVEAL_OPENXR_CAPTURE_DIR=" + rig_.path("capture"), "FOVEAL_OPENXR_CAPTURE_FRAME=2"});
  run_app({"--frames", "3", "--stereo", "--still", "--save-frame", "2", "--save-dir", rig_.path("full")}, "full",
          {"FOVEAL_OPENXR_DISABLE=1"});
  auto composed = image::load(rig_.path("capture/composed.png"));
  ASSERT_TRUE(composed) << composed.error().message << "\n" << rig_.err("quad");
  auto l = image::load(rig_.path("full/view_0.png")), r = image::load(rig_.path("full/view_1.png"));
  ASSERT_TRUE(l && r) << rig_.err("full");
  const image::Image full = side_by_side(*l, *r);
  ASSERT_EQ(composed->width, full.width) << "the layer's stereo images are the runtime's recommended size";
  ASSERT_EQ(composed->height, full.height);

  const std::string golden = test::source_path("tests/openxr/golden/quad_composed_fixed_inset.png");
  if (const char* u = std::getenv("FOVEAL_UPDATE_GOLDEN"); u && std::string(u) == "1") {
    ASSERT_TRUE(image::save_png(golden, *composed));
  } else {
    auto ref = image::load(golden);
    ASSERT_TRUE(ref) << ref.error().message << " (FOVEAL_UPDATE_GOLDEN=1 writes it)";
    const double p = image::psnr(*ref, *composed);
    if (p < 40.0) {
      (void)image::save_png(rig_.path("composed.diff.png"), image::diff_image(*ref, *composed));
      std::filesystem::copy_file(rig_.path("composed.diff.png"), std::string(FOVEAL_BIN_DIR) + "/../quad_composed.diff.png",
                                 std::filesystem::copy_options::overwrite_existing);
    }
    EXPECT_GE(p, 40.0) << "PSNR against the golden image; diff in build/quad_composed.diff.png";
  }

  // Inside each inner view the composed image is the full-density one; outside, the
  // outer view's lower density shows.
  const auto fs = frames(quad);
  ASSERT_GE(fs.size(), 3u);  // without foveald every frame's views are the same: any frame's fields serve
  const int eye_w = l->width;
  for (int e = 0; e < 2; ++e) {
    const image::Rect in = inside_inner(fs[2], e, eye_w, l->height);
    ASSERT_GT(in.w, 10);
    ASSERT_GT(in.h, 10);
    const double inside = image::psnr(full, *composed, in);
    const double whole = image::psnr(image::Image(side_by_side(*l, *r)), *composed, {e * eye_w, 0, eye_w, l->height});
    std::printf("eye %d: PSNR against the full-density frame %.1f dB inside the inner view, %.1f dB over the eye\n", e,
                inside, whole);
    EXPECT_GE(inside, 35.0) << "eye " << e << ": the inner view is not what the composed image shows there";
    EXPECT_LT(whole, inside) << "eye " << e << ": the outer view shows no loss of density";
  }
}

TEST_F(QuadViews, AStereoAppsFramesAreTheSameByteForByteWithTheLayerOnAndOff) {
  std::filesystem::create_directories(rig_.path("on"));
  std::filesystem::create_directories(rig_.path("off"));
  const auto on = run_app({"--frames", "3", "--stereo", "--still", "--save-frame", "2", "--save-dir", rig_.path("on")}, "on");
  const auto off = run_app({"--frames", "3", "--stereo", "--still", "--save-frame", "2", "--save-dir", rig_.path("off")},
                           "off", {"FOVEAL_OPENXR_DISABLE=1"});
  EXPECT_EQ(event(on, "views"), event(off, "views"));
  for (int v = 0; v < 2; ++v) {
    const std::string name = "/view_" + std::to_string(v) + ".png";
    const std::string a = test::read_file(rig_.path("on") + name), b = test::read_file(rig_.path("off") + name);
    ASSERT_FALSE(a.empty());
    EXPECT_TRUE(a == b) << name << " differs with the layer on";
  }
}

// Issue 37 item 2: FOVEAL_OPENXR_QUALITY=jod:T sizes the views from the display model's
// inset levels table (docs/openxr.md, "Sizes"), with the EFR ratio of foveald's pair
// (without foveald the default profile's, 3/2, the right eye dominant).
TEST_F(QuadViews, QualityJodSizesTheViewsFromTheInsetLevelsTable) {
  const auto stereo = run_app({"--frames", "2", "--stereo"}, "stereo");
  const json stereo_sizes = event(stereo, "views")["sizes"];
  ASSERT_EQ(stereo_sizes.size(), 2u) << rig_.err("stereo");
  const auto lines = run_app({"--frames", "2"}, "quality", {"FOVEAL_OPENXR_QUALITY=jod:9.5", "FOVEAL_OPENXR_DISPLAY=htc_vive_pro_eye"});
  const json views = event(lines, "views");
  ASSERT_EQ(views.value("configuration", ""), "quad") << rig_.err("quality");
  ASSERT_TRUE(views["foveated"].get<bool>());
  auto chosen = inset_quality("jod:9.5", test::source_path("data/display/htc_vive_pro_eye.json"), 1.5);
  ASSERT_TRUE(chosen) << chosen.error().message;
  ASSERT_TRUE(chosen->has_value());
  const InsetLevels& l = **chosen;
  const double sigma[2] = {l.sigma_nd, l.sigma_d};
  auto scaled = [](double n, double k) { return std::max(16L, std::lround(n * static_cast<float>(k))); };
  const json& sz = views["sizes"];
  for (int e = 0; e < 2; ++e) {
    const double w = stereo_sizes[e][0].get<double>(), h = stereo_sizes[e][1].get<double>();
    EXPECT_EQ(sz[e][0].get<long>(), scaled(w, 1 / sigma[e])) << "outer width, eye " << e << ", sigma " << sigma[e];
    EXPECT_EQ(sz[e][1].get<long>(), scaled(h, 1 / sigma[e])) << "outer height, eye " << e;
    EXPECT_EQ(sz[e + 2][0].get<long>(), scaled(w, l.share_x)) << "inner width, eye " << e << ", extent " << l.extent_deg;
    EXPECT_EQ(sz[e + 2][1].get<long>(), scaled(h, l.share_y)) << "inner height, eye " << e;
  }
}

}  // namespace
}  // namespace foveal
