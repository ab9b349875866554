// foveal's OpenXR layer against a real runtime: Monado (headless, simulated HMD) through
// the Khronos loader with the core validation layer, an app that reads gaze as any app
// does (examples/openxr_gaze), and foveald serving recorded or synthetic gaze.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <optional>
#include <filesystem>

#include <atomic>
#include <fstream>
#include <thread>

#include "foveal/runtime/fovea_shm.hpp"
#include "openxr_harness.hpp"

namespace foveal {
namespace {

using test::OpenXRRig;
using nlohmann::json;

constexpr const char* kLayerShare = FOVEAL_TEST_LAYER_SHARE;  // the build tree's manifests

class OpenXRLayer : public test::OpenXRTest {
 protected:
  std::vector<json> gaze_lines(const std::string& name = "app") const {
    std::vector<json> g;
    for (const json& l : rig_.lines(name))
      if (l.is_object() && l.value("event", "") == "gaze") g.push_back(l);
    return g;
  }
  json system_line(const std::string& name = "app") const {
    for (const json& l : rig_.lines(name))
      if (l.is_object() && l.value("event", "") == "system") return l;
    return json::object();
  }
};

/// The combined direction the layer gives for a trace row: the tracked eyes' mean.
glm::vec3 combined(const test::TraceRow& r) {
  glm::vec3 s{0};
  for (int e = 0; e < 2; ++e)
    if (r.tracked[e]) s += r.dir[e];
  return glm::normalize(s);
}

/// The app's gaze against foveald's trace: directions, sample times, and inactive
/// exactly where both eyes are in a blink (away from the edges of one).
struct Agreement {
  int active = 0, matched = 0, inactive_in_blink = 0, blink_lines = 0, active_after_blink = 0;
  double worst_deg = 0, worst_time_ms = 0;
};

Agreement compare_with_trace(const std::vector<json>& lines, const std::vector<test::TraceRow>& rows, bool per_eye) {
  Agreement a;
  bool seen_blink = false;
  for (const json& l : lines) {
    const long i = test::row_at(rows, l["t_ns"].get<TimeNs>());
    if (i < 1 || i + 1 >= static_cast<long>(rows.size())) continue;
    auto both_out = [&](long k) { return !rows[k].tracked[0] && !rows[k].tracked[1]; };
    const bool blink = both_out(i) && both_out(i - 1) && both_out(i + 1);
    const bool clear = !both_out(i) && !both_out(i - 1) && !both_out(i + 1);
    if (blink) {
      ++a.blink_lines;
      a.inactive_in_blink += !l["active"].get<bool>();
      seen_blink = true;
    }
    if (!l["active"].get<bool>() || !clear) continue;
    ++a.active;
    a.active_after_blink += seen_blink;
    // The sample the layer located: the row with its time.
    const TimeNs s = l["sample_t_ns"].get<TimeNs>();
    auto nearest = std::min_element(rows.begin(), rows.end(), [s](const auto& x, const auto& y) {
      return std::llabs(x.t_ns - s) < std::llabs(y.t_ns - s);
    });
    a.worst_time_ms = std::max(a.worst_time_ms, static_cast<double>(std::llabs(nearest->t_ns - s)) / 1e6);
    if (std::llabs(nearest->t_ns - s) > 2 * kNsPerMs) continue;
    double err = test::angle_deg(test::vec(l["head_direction"]), combined(*nearest));
    if (per_eye) {
      // The per-eye call read its own sample: the row of its time.
      const TimeNs se = l["eyes_t_ns"].get<TimeNs>();
      const test::TraceRow* row = nullptr;
      for (const auto& r : rows)
        if (std::llabs(r.t_ns - se) <= 2 * kNsPerMs) row = &r;
      if (!row) err = 180;
      for (int e = 0; row && e < 2; ++e) {
        const json& eye = l["eyes"][e];
        if (eye["valid"].get<bool>() != row->tracked[e]) err = 180;
        if (row->tracked[e]) {
          err = std::max(err, test::angle_deg(test::vec(eye["direction"]), row->dir[e]));
          if (std::abs(eye["confidence"].get<double>() - row->confidence[e]) > 0.006) err = 180;
          if (std::abs(eye["position"][0].get<double>() - (e == 0 ? -0.0315 : 0.0315)) > 1e-4) err = 180;
        }
      }
    }
    a.worst_deg = std::max(a.worst_deg, err);
    ++a.matched;
  }
  return a;
}

TEST_F(OpenXRLayer, RecordedGazeReachesTheAppAsFovealdTracedIt) {
  // (b) the bundled Vive recording; (c) per eye through XR_FB_eye_tracking_social.
  auto fd = rig_.foveald({"--no-render", "--duration", "600", "--out", rig_.path("fd")}, "foveald");
  wait_for_block();
  // Prediction off: this test checks the transport, each locate against the traced sample
  // exactly (prediction to the locate's time has its own test below).
  auto app = rig_.app({"--duration", "6", "--per-eye"}, rig_.app_env(kLayerShare, {"FOVEAL_OPENXR_PREDICT=off"}));
  ASSERT_EQ(app->wait(30000), 0) << rig_.err();
  fd->signal(SIGTERM);  // foveald serves until the app is done (its 600 s are a hang guard)
  ASSERT_EQ(fd->wait(test::kExitsWithinMs), 0) << rig_.err("foveald");
  const json sys = system_line();
  EXPECT_EQ(sys.value("supportsEyeGazeInteraction", -1), 1) << sys.dump();
  EXPECT_EQ(sys.value("supportsEyeTracking", -1), 1) << sys.dump();
  const auto lines = gaze_lines();
  const auto rows = test::read_trace(rig_.path("fd"), DisplayModel::vive_pro_eye());
  ASSERT_GT(rows.size(), 500u);
  const Agreement a = compare_with_trace(lines, rows, /*per_eye=*/true);
  std::printf("recorded: %d active lines, worst %.4f deg from the trace, worst sample time %.3f ms, %d/%d blink lines inactive\n",
              a.active, a.worst_deg, a.worst_time_ms, a.inactive_in_blink, a.blink_lines);
  EXPECT_GT(a.active, 300) << "of " << lines.size() << " lines; " << rig_.err();
  EXPECT_EQ(a.matched, a.active) << "samples more than 2 ms from any trace row (worst " << a.worst_time_ms << " ms)";
  EXPECT_LT(a.worst_deg, 0.01) << "degrees between the app's gaze and foveald's trace";
  EXPECT_EQ(a.inactive_in_blink, a.blink_lines);
  // The app's last reading comes after xrRequestExitSession (STOPPING): no focus, no gaze.
  int unfocused = 0;
  for (const json& l : lines)
    if (l["state"] != "FOCUSED") {
      ++unfocused;
      EXPECT_FALSE(l["active"].get<bool>()) << l.dump();
      EXPECT_FALSE(l["eyes"][0]["valid"].get<bool>()) << l.dump();
    }
  EXPECT_EQ(unfocused, 1);
  // Only foveal's one line of state: the validation layer found no misuse.
  EXPECT_EQ(rig_.err().find("VALIDATION"), std::string::npos) << rig_.err();
}

TEST_F(OpenXRLayer, SyntheticScanpathWithinHalfADegreeOfTheTruthAndInactiveThroughBlinks) {
  // (a) a scanpath with known truth, replayed through foveald's gaze pipeline.
  const test::RunResult synth = test::run(test::bin("foveal") + " synth --seed 11 --duration 14 --noise 0.2 --blink-rate 1.5 -o " +
                                          rig_.path("synth.csv") + " --truth " + rig_.path("truth.csv"));
  ASSERT_EQ(synth.exit_code, 0) << synth.err;
  auto fd = rig_.foveald({"--source", "replay:" + rig_.path("synth.csv"), "--no-render", "--out", rig_.path("fd")}, "foveald");
  wait_for_block();
  auto app = rig_.app({"--duration", "10"}, rig_.app_env(kLayerShare, {"FOVEAL_OPENXR_PREDICT=off"}));  // exact, as above
  ASSERT_EQ(app->wait(30000), 0) << rig_.err();
  ASSERT_EQ(fd->wait(30000), 0) << rig_.err("foveald");
  const auto lines = gaze_lines();
  const auto rows = test::read_trace(rig_.path("fd"), DisplayModel::vive_pro_eye());
  const Agreement a = compare_with_trace(lines, rows, false);
  std::printf("synthetic: %d active lines (%d after a blink), worst %.4f deg from the trace, %d/%d blink lines inactive\n",
              a.active, a.active_after_blink, a.worst_deg, a.inactive_in_blink, a.blink_lines);
  EXPECT_GT(a.blink_lines, 5) << "the run saw no blink: pick another seed";
  EXPECT_EQ(a.inactive_in_blink, a.blink_lines) << "active during a blink";
  EXPECT_GT(a.active_after_blink, 50) << "not active again after a blink";
  EXPECT_EQ(a.matched, a.active) << "worst sample time " << a.worst_time_ms << " ms";

  // Against the truth: settled fixations (50 ms in, the filter's stated settling time,
  // docs/filtering.md), where the pipeline's lag is within a sample.
  using Truth = test::TruthRow;
  const std::vector<Truth> truth = test::read_truth(rig_.path("truth.csv"), rig_.path("fd"));
  auto truth_at = [&](TimeNs t) -> const Truth* {
    const Truth* best = nullptr;
    for (const Truth& x : truth)
      if (std::llabs(x.t - t) <= 2 * kNsPerMs) best = &x;
    return best;
  };
  int settled = 0, within = 0;
  double worst = 0;
  for (const json& l : lines) {
    if (!l["active"].get<bool>()) continue;
    const TimeNs s = l["sample_t_ns"].get<TimeNs>();
    const Truth* now = truth_at(s);
    const Truth* before = truth_at(s - 50 * kNsPerMs);
    if (!now || !before || now->event != "fixation" || before->event != "fixation" || before->index != now->index) continue;
    const double e = test::angle_deg(test::vec(l["head_direction"]), now->combined());
    ++settled;
    within += e <= 0.5;
    worst = std::max(worst, e);
  }
  std::printf("synthetic: %d settled fixation samples, %d within 0.5 deg of the truth, worst %.3f deg\n", settled, within,
              worst);
  ASSERT_GT(settled, 200);
  EXPECT_EQ(within, settled) << "settled fixation samples within 0.5 deg of the truth; worst " << worst << " deg";
}

TEST_F(OpenXRLayer, WithoutFovealdTheAppRunsAndTheGazeIsInactive) {
  // (d) no foveald at all: the extension is still there, the gaze inactive, one line said.
  auto app = rig_.app({"--duration", "2", "--per-eye"}, rig_.app_env(kLayerShare));
  ASSERT_EQ(app->wait(30000), 0) << rig_.err();
  EXPECT_EQ(system_line().value("supportsEyeGazeInteraction", -1), 1);
  const auto lines = gaze_lines();
  ASSERT_GT(lines.size(), 50u) << rig_.err();
  for (const json& l : lines) {
    EXPECT_FALSE(l["active"].get<bool>());
    EXPECT_EQ(l["flags"].get<int>(), 0);
    EXPECT_FALSE(l["eyes"][0]["valid"].get<bool>());
  }
  const std::string err = rig_.err();
  const auto first = err.find("foveal-openxr: no gaze from foveald yet");
  EXPECT_NE(first, std::string::npos) << err;
  EXPECT_EQ(err.find("foveal-openxr: no gaze from foveald yet", first + 1), std::string::npos) << "said more than once";
}

TEST_F(OpenXRLayer, FovealdKilledAndRestartedMidSession) {
  // (d) the app keeps running: active, inactive once foveald is gone, active again. Each
  // phase waits for the app's lines that show it, not for a time (the app's 600 s are a
  // hang guard; it is stopped once the last phase is seen).
  auto app = rig_.app({"--duration", "600"}, rig_.app_env(kLayerShare));
  const auto count = [this](auto&& pred) {
    int n = 0;
    for (const json& l : gaze_lines()) n += pred(l["t_ns"].get<TimeNs>(), l["active"].get<bool>());
    return n;
  };
  ASSERT_TRUE(test::eventually([&] { return rig_.err().find("no gaze from foveald yet") != std::string::npos; }))
      << rig_.err();
  auto fd = rig_.foveald({"--no-render", "--out", rig_.path("fd1")}, "foveald");
  ASSERT_TRUE(test::eventually([&] { return count([](TimeNs, bool a) { return a; }) > 50; })) << rig_.err();
  fd->signal(SIGKILL);
  const TimeNs killed = monotonic_now_ns();
  ASSERT_EQ(fd->wait(test::kExitsWithinMs), 128 + SIGKILL);
  // Lines from half a second after the kill on (the layer sees a dead writer at its next
  // read; the margin only keeps a line stamped before the kill out).
  const auto gone = [&](TimeNs t, bool) { return t > killed + 500 * kNsPerMs; };
  // ... and it says so once it takes foveald for gone (no heartbeat for 2 s).
  ASSERT_TRUE(test::eventually([&] { return count(gone) > 100 && rig_.err().find("foveald stopped") != std::string::npos; }))
      << rig_.err();
  const TimeNs restarted = monotonic_now_ns();
  auto fd2 = rig_.foveald({"--no-render", "--out", rig_.path("fd2")}, "foveald2");
  const auto back = [&](TimeNs t, bool a) { return a && t > restarted; };
  ASSERT_TRUE(test::eventually([&] { return count(back) > 50; })) << "not active again after foveald came back: " << rig_.err();
  ASSERT_EQ(app->wait(1), -1) << "the app did not survive: " << rig_.err();  // still running
  app->signal(SIGTERM);
  EXPECT_EQ(app->wait(test::kExitsWithinMs), 128 + SIGTERM);
  const int before = count([&](TimeNs t, bool a) { return a && t < killed; });
  const int gone_active = count([&](TimeNs t, bool a) { return a && t > killed + 500 * kNsPerMs && t < restarted; });
  EXPECT_GT(before, 50) << rig_.err();
  EXPECT_EQ(gone_active, 0) << "active without foveald";
}

TEST_F(OpenXRLayer, InstalledPrefixIsFoundByTheLoaderAndOffTurnsItOff) {
  // (e) cmake --install into a prefix; the app sees only that prefix's manifest.
  const std::string prefix = rig_.path("prefix");
  for (const char* component : {"sdk", "openxr"}) {
    const test::RunResult r = test::run(std::string(FOVEAL_CMAKE_COMMAND) + " --install " FOVEAL_BUILD_DIR " --component " +
                                        component + " --prefix " + prefix);
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  }
  const std::string manifest = prefix + "/share/openxr/1/api_layers/implicit.d/XrApiLayer_foveal_gaze.json";
  ASSERT_TRUE(std::filesystem::exists(manifest));
  const json m = json::parse(test::read_file(manifest));
  EXPECT_EQ(m["api_layer"]["disable_environment"], "FOVEAL_OPENXR_DISABLE");
  EXPECT_EQ(m["api_layer"]["library_path"].get<std::string>().rfind("../", 0), 0u) << "relative to the manifest";

  auto fd = rig_.foveald({"--no-render", "--duration", "600", "--out", rig_.path("fd")}, "foveald");
  wait_for_block();
  auto app = rig_.app({"--duration", "1.5"}, rig_.app_env(prefix + "/share"), "installed");
  ASSERT_EQ(app->wait(30000), 0) << rig_.err("installed");
  const json sys = system_line("installed");
  const auto layers = sys.value("api_layers", json::array());
  EXPECT_NE(std::find(layers.begin(), layers.end(), "XR_APILAYER_FOVEAL_gaze"), layers.end()) << sys.dump();
  EXPECT_EQ(sys.value("supportsEyeGazeInteraction", -1), 1) << sys.dump();
  int active = 0;
  for (const json& l : gaze_lines("installed")) active += l["active"].get<bool>();
  EXPECT_GT(active, 20) << rig_.err("installed");

  // The manifest's off switch: the runtime's own answer (Monado's simulated HMD: none).
  auto off = rig_.app({"--duration", "0.5"}, rig_.app_env(prefix + "/share", {"FOVEAL_OPENXR_DISABLE=1"}), "off");
  ASSERT_EQ(off->wait(30000), 0) << rig_.err("off");
  const json sys_off = system_line("off");
  const auto layers_off = sys_off.value("api_layers", json::array());
  EXPECT_EQ(std::find(layers_off.begin(), layers_off.end(), "XR_APILAYER_FOVEAL_gaze"), layers_off.end());
  EXPECT_EQ(sys_off.value("supportsEyeGazeInteraction", -1), 0) << sys_off.dump();
}

TEST_F(OpenXRLayer, RuntimeModePassesEverythingThrough) {
  // FOVEAL_OPENXR_GAZE=runtime: the runtime answers, as it does without the layer.
  auto app = rig_.app({"--duration", "0.5"}, rig_.app_env(kLayerShare, {"FOVEAL_OPENXR_GAZE=runtime"}));
  ASSERT_EQ(app->wait(30000), 0) << rig_.err();
  EXPECT_EQ(system_line().value("supportsEyeGazeInteraction", -1), 0);
}

TEST_F(OpenXRLayer, StatusCommandNamesTheLayerTheRuntimeAndFoveald) {
  // `foveal openxr --json`, from the environment an app would start in.
  auto fd = rig_.foveald({"--no-render", "--duration", "600", "--out", rig_.path("fd")}, "foveald");
  wait_for_block();
  auto status = [&](const std::vector<std::string>& extra, const std::string& name) {
    test::Child c({test::bin("foveal"), "openxr", "--json"}, rig_.app_env(kLayerShare, extra), rig_.path(name + ".out"),
                  rig_.path(name + ".err"));
    EXPECT_EQ(c.wait(30000), 0) << rig_.err(name);
    return json::parse(test::read_file(rig_.path(name + ".out")), nullptr, false);
  };
  const json on = status({}, "status");
  ASSERT_TRUE(on.is_object()) << rig_.err("status");
  EXPECT_TRUE(on["layer"]["enabled"].get<bool>()) << on.dump(2);
  EXPECT_EQ(on["layer"]["manifests"][0]["kind"], "implicit");
  EXPECT_TRUE(on["layer"]["manifests"][0]["library_exists"].get<bool>());
  EXPECT_EQ(on["runtime"]["manifest"], FOVEAL_TEST_OPENXR_RUNTIME);
  EXPECT_EQ(on["runtime"]["chosen_by"], "XR_RUNTIME_JSON");
  EXPECT_TRUE(on["runtime"]["probed"].get<bool>()) << on.dump(2);
  EXPECT_TRUE(on["runtime"]["lists_eye_gaze_interaction"].get<bool>());
  EXPECT_FALSE(on["runtime"]["own_eye_gaze"].get<bool>());  // Monado's simulated HMD has none
  EXPECT_TRUE(on["foveald"]["serving"].get<bool>()) << on.dump(2);
  EXPECT_EQ(on["verdict"], "apps get foveald's gaze");
  const json off = status({"FOVEAL_OPENXR_DISABLE=1"}, "status_off");
  EXPECT_FALSE(off["layer"]["enabled"].get<bool>()) << off.dump(2);
  EXPECT_NE(off["layer"]["why"].get<std::string>().find("FOVEAL_OPENXR_DISABLE"), std::string::npos);
}

}  // namespace
}  // namespace foveal

namespace foveal {
namespace {

TEST_F(OpenXRLayer, ANewActionSetBindsGazeAndTwoLocatesInAFrameAgreeWithTheActionState) {
  // Issue 37 item 0 (a, c): a next session's own action set takes the eye-gaze binding
  // (the layer refused it once any set was attached), and the gaze located in LOCAL and
  // in VIEW in one reading is tracked in both or neither, as the action state says.
  auto fd = rig_.foveald({"--no-render", "--duration", "600", "--out", rig_.path("fd")}, "foveald");
  wait_for_block();
  auto app = rig_.app({"--duration", "4", "--second-set"}, rig_.app_env(kLayerShare));
  ASSERT_EQ(app->wait(30000), 0) << rig_.err();
  fd->signal(SIGTERM);
  ASSERT_EQ(fd->wait(20000), 0) << rig_.err("foveald");
  int lines = 0, active = 0;
  json second, destroyed;
  for (const json& l : rig_.lines()) {
    if (!l.is_object()) continue;
    if (l.value("event", "") == "second_set") second = l;
    if (l.value("event", "") == "destroyed") destroyed = l;
    if (l.value("event", "") != "gaze") continue;
    ++lines;
    const bool in_local = l["flags"].get<unsigned long long>() != 0, in_view = l["view_flags"].get<unsigned long long>() != 0;
    EXPECT_EQ(in_local, in_view) << l.dump();
    EXPECT_EQ(in_local, l["active"].get<bool>()) << l.dump();
    active += l["active"].get<bool>();
  }
  EXPECT_GT(active, 20) << "of " << lines << " readings; " << rig_.err();
  ASSERT_TRUE(second.contains("suggest")) << rig_.err();
  EXPECT_EQ(second["suggest"].get<int>(), 0) << "XR_ERROR_ACTIONSETS_ALREADY_ATTACHED is -46";
  std::printf("xrDestroyInstance took %.1f ms (the feed's thread is woken, not waited out)\n",
              destroyed.value("destroy_instance_ms", -1.0));
}

TEST_F(OpenXRLayer, AFifoAtTheBlocksNameNeitherHangsTheAppNorItsExit) {
  // Issue 38 items 1 and 2: a FIFO where the block should be, there from the start or
  // planted while the app runs. The layer's open is non-blocking and refuses it; the app
  // reads no gaze, runs its time and quits (xrDestroyInstance joins the feed's thread).
  const std::string fifo = "/dev/shm" + rig_.shm();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);
  auto before = rig_.app({"--duration", "2"}, rig_.app_env(kLayerShare), "before");
  const int rc_before = before->wait(60000);
  ::unlink(fifo.c_str());
  ASSERT_EQ(rc_before, 0) << "-1: the app hung on the FIFO; " << rig_.err("before");
  EXPECT_NE(rig_.err("before").find("FIFO"), std::string::npos) << rig_.err("before");

  auto during = rig_.app({"--duration", "4"}, rig_.app_env(kLayerShare), "during");
  for (int i = 0; i < 30000 && rig_.err("during").find("no gaze from foveald yet") == std::string::npos; ++i)
    sleep_until_ns(monotonic_now_ns() + kNsPerMs);
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0666), 0);  // found at the feed's next look, 100 ms on
  const int rc_during = during->wait(60000);
  ::unlink(fifo.c_str());
  EXPECT_EQ(rc_during, 0) << "-1: the app hung on the FIFO planted under it; " << rig_.err("during");
  for (const json& l : rig_.lines("during")) {
    if (l.is_object() && l.value("event", "") == "gaze") {
      EXPECT_FALSE(l["active"].get<bool>()) << l.dump();
    }
  }
}

/// How many mappings of the block `shm` process `pid` holds now.
int mappings_of(pid_t pid, const std::string& shm) {
  std::ifstream maps("/proc/" + std::to_string(pid) + "/maps");
  int n = 0;
  for (std::string line; std::getline(maps, line);) n += line.find("/dev/shm" + shm) != std::string::npos;
  return n;
}

TEST_F(OpenXRLayer, ABlockWhoseFoveaIsRefusedIsRetriedWithABackoffAndLeaksNoMappings) {
  // Issue 38 item 3: a live block (its heartbeat kept fresh) whose fovea every reader
  // refuses (confidence 2.0). The layer gave up and remapped it every 100 ms, keeping each
  // mapping (1 -> 121 in 12 s) and logging 20 lines a second.
  auto shm = FoveaShm::create(rig_.shm());
  ASSERT_TRUE(shm) << shm.error().message;
  shm->publish_view(DisplayModel::vive_pro_eye());
  FoveaFrame f;
  f.t_ns = monotonic_now_ns();
  for (auto& e : f.eyes) e = {{720.0f, 800.0f}, FoveaState::fixation, 2.0f, {}, {}, true};
  shm->publish(f, 1440, 1600);
  std::atomic<bool> stop{false};
  std::thread beat([&] {
    while (!stop.load()) {
      shm->heartbeat();
      sleep_until_ns(monotonic_now_ns() + 10 * kNsPerMs);
    }
  });
  auto app = rig_.app({"--duration", "4"}, rig_.app_env(kLayerShare));
  int most = 0, rc = -1;
  for (int i = 0; i < 6000 && (rc = app->wait(1)) < 0; ++i) {  // sampled for as long as the app runs (2 min guard)
    most = std::max(most, mappings_of(app->pid(), rig_.shm()));
    sleep_until_ns(monotonic_now_ns() + 20 * kNsPerMs);
  }
  stop = true;
  beat.join();
  EXPECT_EQ(rc, 0) << rig_.err();
  EXPECT_LE(most, 2) << "mappings of the refused block held at once by the app";
  const std::string err = rig_.err();
  int said = 0;
  for (std::size_t at = err.find("unusable"); at != std::string::npos; at = err.find("unusable", at + 1)) ++said;
  EXPECT_EQ(said, 1) << "one line for the state, not one per try: " << err;
}

/// The truth's combined direction at t, interpolated between its rows, within one event
/// of `kind` (nullopt elsewhere, and at an event's edges).
std::optional<glm::vec3> truth_in(const std::vector<test::TruthRow>& truth, TimeNs t, const std::string& kind) {
  auto after = std::upper_bound(truth.begin(), truth.end(), t, [](TimeNs x, const test::TruthRow& r) { return x < r.t; });
  if (after == truth.begin() || after == truth.end()) return std::nullopt;
  const test::TruthRow& a = *(after - 1);
  const test::TruthRow& b = *after;
  if (a.event != kind || b.event != kind || a.index != b.index || b.t <= a.t) return std::nullopt;
  const float u = static_cast<float>(t - a.t) / static_cast<float>(b.t - a.t);
  return glm::normalize(a.combined() * (1.0f - u) + b.combined() * u);
}

TEST_F(OpenXRLayer, GazeIsPredictedToTheLocatesTimeAndOffLocatesTheSample) {
  // Issue 37 item 0 (d): an app locating at a display time ahead (21 ms: what Monado's
  // predictedDisplayTime is ahead of the newest sample; its headless sessions have no
  // frame loop, so the app asks for now + 21 ms) gets the gaze predicted
  // there by foveald's rule, closer to the truth at that time than the sample it comes
  // from, in smooth pursuit where the sample trails most; XrEyeGazeSampleTimeEXT still
  // names the sample. A second app at the same time with FOVEAL_OPENXR_PREDICT=off gets
  // the sample exactly.
  const test::RunResult synth = test::run(test::bin("foveal") + " synth --seed 5 --duration 14 --noise 0.1 --blink-rate 0.1 " +
                                          "--pursuit 0.7 -o " + rig_.path("synth.csv") + " --truth " + rig_.path("truth.csv"));
  ASSERT_EQ(synth.exit_code, 0) << synth.err;
  auto fd = rig_.foveald({"--source", "replay:" + rig_.path("synth.csv"), "--no-render", "--out", rig_.path("fd")}, "foveald");
  wait_for_block();
  auto on = rig_.app({"--duration", "10", "--ahead-ms", "21"}, rig_.app_env(kLayerShare), "on");
  auto off = rig_.app({"--duration", "10", "--ahead-ms", "21"}, rig_.app_env(kLayerShare, {"FOVEAL_OPENXR_PREDICT=off"}), "off");
  ASSERT_EQ(on->wait(40000), 0) << rig_.err("on");
  ASSERT_EQ(off->wait(40000), 0) << rig_.err("off");
  ASSERT_EQ(fd->wait(30000), 0) << rig_.err("foveald");
  const auto rows = test::read_trace(rig_.path("fd"), DisplayModel::vive_pro_eye());
  const std::vector<test::TruthRow> truth = test::read_truth(rig_.path("truth.csv"), rig_.path("fd"));

  // Off: the sample, exactly, whatever time the app asks for.
  const auto off_lines = gaze_lines("off");
  const Agreement a = compare_with_trace(off_lines, rows, false);
  std::printf("prediction off: %d active lines, worst %.4f deg from the traced sample\n", a.active, a.worst_deg);
  EXPECT_GT(a.active, 100) << rig_.err("off");
  EXPECT_EQ(a.matched, a.active) << "worst sample time " << a.worst_time_ms << " ms";
  EXPECT_LT(a.worst_deg, 0.01) << "off must locate the sample itself";

  // On, in pursuit: the located gaze and the sample it came from, each against the truth
  // at the time the app asked for.
  std::vector<double> predicted, sampled, horizon_ms;
  int off_trace = 0;
  for (const json& l : gaze_lines("on")) {
    if (!l["active"].get<bool>()) continue;
    const TimeNs t = l["t_ns"].get<TimeNs>(), s = l["sample_t_ns"].get<TimeNs>();
    // The reported time is the sample's own: a row of foveald's trace.
    auto nearest = std::min_element(rows.begin(), rows.end(), [s](const auto& x, const auto& y) {
      return std::llabs(x.t_ns - s) < std::llabs(y.t_ns - s);
    });
    if (nearest == rows.end() || std::llabs(nearest->t_ns - s) > 2 * kNsPerMs) {
      ++off_trace;
      continue;
    }
    if (t <= s || !nearest->tracked[0] || !nearest->tracked[1]) continue;
    const auto at_t = truth_in(truth, t, "pursuit");
    const auto at_s = truth_in(truth, s - 50 * kNsPerMs, "pursuit");  // well into the pursuit: the filter has its velocity
    if (!at_t || !at_s) continue;
    predicted.push_back(test::angle_deg(test::vec(l["head_direction"]), *at_t));
    sampled.push_back(test::angle_deg(combined(*nearest), *at_t));
    horizon_ms.push_back(static_cast<double>(t - s) / 1e6);
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  auto mean = [](const std::vector<double>& v) {
    double sum = 0;
    for (double x : v) sum += x;
    return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
  };
  std::printf("prediction on: %zu pursuit readings, horizon median %.1f ms; error against the truth at the asked time: "
              "predicted median %.3f mean %.3f deg, the sample median %.3f mean %.3f deg\n",
              predicted.size(), median(horizon_ms), median(predicted), mean(predicted), median(sampled), mean(sampled));
  EXPECT_EQ(off_trace, 0) << "XrEyeGazeSampleTimeEXT must name the sample's time";
  ASSERT_GT(predicted.size(), 100u) << "too few readings in pursuit: " << rig_.err("on");
  EXPECT_LT(median(predicted), 0.5 * median(sampled)) << "prediction must bring the gaze clearly closer to the truth";
  EXPECT_LT(mean(predicted), 0.5 * mean(sampled));
}

}  // namespace
}  // namespace foveal

namespace foveal {
namespace {

/// One location as openxr_gaze prints it, against another: the same flags, the same pose
/// within `tol` per component.
void expect_same_location(const json& a, const json& b, double tol, const std::string& what) {
  EXPECT_EQ(a["flags"], b["flags"]) << what << ": " << a.dump() << " against " << b.dump();
  for (const char* k : {"orientation", "position"})
    for (std::size_t i = 0; i < a[k].size(); ++i)
      EXPECT_NEAR(a[k][i].get<double>(), b[k][i].get<double>(), tol) << what << " " << k << "[" << i << "]";
}

TEST_F(OpenXRLayer, LocateSpacesAnswersTheGazeSpaceAsLocateSpaceDoes) {
  // Issue 37 item 1: an app that locates the gaze space through xrLocateSpaces (here
  // xrLocateSpacesKHR: Debian's loader takes no 1.1 instance, see the next test) gets,
  // in the same reading at the same time, what xrLocateSpace gives: the same pose and
  // flags for the gaze space in LOCAL and for LOCAL in the gaze space (a base of the
  // layer's), the runtime's own answer for VIEW in the same call, and no velocity for the
  // gaze. Without the layer's interception the runtime answers the gaze space as an action
  // space bound to nothing it knows: flags 0.
  auto fd = rig_.foveald({"--no-render", "--duration", "600", "--out", rig_.path("fd")}, "foveald");
  wait_for_block();
  auto app = rig_.app({"--duration", "3", "--locate-spaces"}, rig_.app_env(kLayerShare));
  ASSERT_EQ(app->wait(30000), 0) << rig_.err();
  fd->signal(SIGTERM);
  ASSERT_EQ(fd->wait(20000), 0) << rig_.err("foveald");
  ASSERT_EQ(system_line().value("locate_spaces", ""), "xrLocateSpacesKHR") << system_line().dump();
  int active = 0, inactive = 0;
  for (const json& l : gaze_lines()) {
    ASSERT_TRUE(l.contains("spaces")) << l.dump();
    const json& one = l["single"];
    const json& many = l["spaces"];
    // The gaze: the latched sample predicted to the same time, so the same bits.
    expect_same_location(many["gaze"], one["gaze"], 1e-7, "gaze in LOCAL");
    expect_same_location(many["local_in_gaze"], one["local_in_gaze"], 1e-7, "LOCAL in the gaze space");
    expect_same_location(many["view"], one["view"], 1e-6, "VIEW in LOCAL (the runtime's)");
    EXPECT_EQ(many["velocity_flags"][0].get<int>(), 0) << "no velocity for the gaze";
    const bool tracked = one["gaze"]["flags"].get<int>() != 0;
    EXPECT_EQ(tracked, l["active"].get<bool>()) << l.dump();
    (tracked ? active : inactive)++;
  }
  std::printf("xrLocateSpaces against xrLocateSpace: %d active readings, %d inactive, all equal\n", active, inactive);
  EXPECT_GT(active, 20) << rig_.err();
}

TEST_F(OpenXRLayer, AnOpenXR11InstanceGetsTheInsetConfigurationOnlyWhereTheRuntimeTakesIt) {
  // Issue 37 item 1: apiVersion goes down as the app asked. Where the chain below refuses
  // it (XR_ERROR_API_VERSION_UNSUPPORTED, -4), the app gets that, as without the layer;
  // where the runtime takes 1.1, the app sees PRIMARY_STEREO_WITH_FOVEATED_INSET
  // (1000037000) without XR_VARJO_quad_views, and xrLocateSpaces (core) answers the gaze
  // space as xrLocateSpace. Debian's loader (1.0.20) refuses 1.1 itself, before any layer
  // ("Max supported version is 1.0"), so the 1.1 instances go through a stand-in loader
  // (direct_loader.cpp: the layer chained over Monado, nothing else). Monado 8f85280
  // takes 1.0 and 1.1 and refuses 1.2.
  auto fd = rig_.foveald({"--no-render", "--duration", "600", "--out", rig_.path("fd")}, "foveald");
  wait_for_block();
  auto first_line = [&](const std::string& name) {
    const auto lines = rig_.lines(name);
    return lines.empty() || !lines[0].is_object() ? json::object() : lines[0];
  };
  auto has_inset = [](const json& sys) {
    const json v = sys.value("view_configurations", json::array());
    return std::find(v.begin(), v.end(), 1000037000) != v.end();
  };

  // Debian's loader: refused before any layer, the same answer with the layer as without.
  auto sys_off = rig_.app({"--api", "1.1", "--duration", "0.5"}, rig_.app_env(kLayerShare, {"FOVEAL_OPENXR_DISABLE=1"}), "sys_off");
  auto sys_on = rig_.app({"--api", "1.1", "--duration", "0.5"}, rig_.app_env(kLayerShare), "sys_on");
  const int rc_sys_off = sys_off->wait(30000), rc_sys_on = sys_on->wait(30000);
  if (first_line("sys_off").value("event", "") == "instance") {
    EXPECT_EQ(rc_sys_off, 1);
    EXPECT_EQ(rc_sys_on, 1) << rig_.err("sys_on");
    EXPECT_EQ(first_line("sys_on"), first_line("sys_off")) << rig_.err("sys_on");
    EXPECT_EQ(first_line("sys_off").value("result", 0), -4) << "XR_ERROR_API_VERSION_UNSUPPORTED";
  }

  // The stand-in loader: Monado answers the version itself.
  auto direct = [&](const std::string& api, bool with_layer, const std::string& name, std::vector<std::string> args) {
    args.insert(args.begin(), {"--api", api});
    return rig_.app(args, rig_.app_env(kLayerShare, {"LD_LIBRARY_PATH=" FOVEAL_TEST_DIRECT_LOADER_DIR,
                                                     std::string("FOVEAL_TEST_LAYER_LIBRARY=") +
                                                         (with_layer ? FOVEAL_TEST_LAYER_LIBRARY : "")},
                                     /*validation=*/false),
                    name);
  };
  // 1.2: Monado refuses; the layer hands the app Monado's answer.
  auto v12_off = direct("1.2", false, "v12_off", {"--duration", "0.5"});
  auto v12_on = direct("1.2", true, "v12_on", {"--duration", "0.5"});
  EXPECT_EQ(v12_off->wait(30000), 1) << rig_.err("v12_off");
  EXPECT_EQ(v12_on->wait(30000), 1) << rig_.err("v12_on");
  EXPECT_EQ(first_line("v12_off").value("result", 0), -4) << rig_.err("v12_off");
  EXPECT_EQ(first_line("v12_on"), first_line("v12_off")) << rig_.err("v12_on");
  // 1.0 with the layer and without XR_VARJO_quad_views: no inset configuration.
  auto v10 = direct("1.0", true, "v10", {"--duration", "0.5"});
  ASSERT_EQ(v10->wait(30000), 0) << rig_.err("v10");
  EXPECT_FALSE(has_inset(first_line("v10"))) << first_line("v10").dump();
  // 1.1: taken; the inset configuration with the layer only, and xrLocateSpaces (core).
  auto v11_off = direct("1.1", false, "v11_off", {"--duration", "0.5"});
  ASSERT_EQ(v11_off->wait(30000), 0) << rig_.err("v11_off");
  EXPECT_EQ(first_line("v11_off").value("api_version", ""), "1.1") << rig_.err("v11_off");
  EXPECT_FALSE(has_inset(first_line("v11_off"))) << first_line("v11_off").dump();
  auto v11 = direct("1.1", true, "v11", {"--duration", "3", "--locate-spaces"});
  ASSERT_EQ(v11->wait(30000), 0) << rig_.err("v11");
  const json sys = first_line("v11");
  EXPECT_TRUE(has_inset(sys)) << sys.dump();
  EXPECT_EQ(sys.value("locate_spaces", ""), "xrLocateSpaces") << sys.dump();
  int active = 0, readings = 0;
  for (const json& l : gaze_lines("v11")) {
    ++readings;
    expect_same_location(l["spaces"]["gaze"], l["single"]["gaze"], 1e-7, "gaze in LOCAL (xrLocateSpaces)");
    expect_same_location(l["spaces"]["local_in_gaze"], l["single"]["local_in_gaze"], 1e-7, "LOCAL in the gaze space");
    active += l["active"].get<bool>();
  }
  std::printf("OpenXR 1.1 through the stand-in loader: inset configuration listed, %d of %d readings active, "
              "xrLocateSpaces equal to xrLocateSpace\n", active, readings);
  EXPECT_GT(active, 20) << rig_.err("v11");
  fd->signal(SIGTERM);
  EXPECT_EQ(fd->wait(20000), 0) << rig_.err("foveald");
}

}  // namespace
}  // namespace foveal
