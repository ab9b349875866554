#pragma once
// The openxr tests' parts: foveald and an OpenXR app (examples/openxr_gaze) as real
// processes, the app on the real Monado through the Khronos loader with the core
// validation layer, both bound to one fovea block of their own.
#include <signal.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <fcntl.h>
#include <atomic>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "csv_rows.hpp"
#include "foveal/core/clock.hpp"
#include "foveal/core/display_model.hpp"
#include "foveal/runtime/fovea_shm.hpp"
#include "test_support.hpp"

namespace foveal::test {

/// A child process with its output in files; killed at scope exit if still running.
class Child {
 public:
  Child(std::vector<std::string> argv, const std::vector<std::string>& env, const std::string& out, const std::string& err) {
    std::vector<char*> a, e;
    std::vector<std::string> env_store = env;
    for (auto& s : argv) a.push_back(s.data());
    a.push_back(nullptr);
    for (auto& s : env_store) e.push_back(s.data());
    e.push_back(nullptr);
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    if (::posix_spawn(&pid_, a[0], &fa, nullptr, a.data(), e.data()) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&fa);
  }
  ~Child() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  bool started() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }
  void signal(int sig) const { if (pid_ > 0) ::kill(pid_, sig); }
  /// The exit code (128 + signal when killed), or -1 when still running after `ms`.
  int wait(int ms) {
    if (pid_ <= 0) return -1;
    const int rc = wait_for_exit(pid_, ms);
    if (rc >= 0) pid_ = -1;
    return rc;
  }

 private:
  pid_t pid_ = -1;
};

inline std::vector<nlohmann::json> json_lines(const std::string& text) {
  std::vector<nlohmann::json> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);)
    if (!l.empty()) lines.push_back(nlohmann::json::parse(l, nullptr, /*allow_exceptions=*/false));
  return lines;
}

inline double angle_deg(const glm::vec3& a, const glm::vec3& b) {
  // In double: near 0 deg a float dot's rounding alone is 0.02 deg.
  const double c = glm::dot(glm::normalize(glm::dvec3(a)), glm::normalize(glm::dvec3(b)));
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / M_PI;
}

inline glm::vec3 vec(const nlohmann::json& j) { return {j[0].get<float>(), j[1].get<float>(), j[2].get<float>()}; }

/// One row of foveald's trace.csv, on CLOCK_MONOTONIC.
struct TraceRow {
  TimeNs t_ns;
  bool tracked[2];
  glm::vec3 dir[2];
  float confidence[2];
};

/// trace.csv through the display model foveald used: each eye's direction as the layer
/// should give it, times moved to CLOCK_MONOTONIC with summary.json's trace_t0_ns.
inline std::vector<TraceRow> read_trace(const std::string& dir, const DisplayModel& m) {
  const auto summary = nlohmann::json::parse(read_file(dir + "/summary.json"), nullptr, false);
  const TimeNs t0 = summary.value("trace_t0_ns", TimeNs{0});
  std::vector<TraceRow> rows;
  for (const CsvRow& r : read_csv_rows(read_file(dir + "/trace.csv"))) {
    if (r.at("left_state").empty() || r.at("left_state") == "marker") continue;
    TraceRow t{t0 + std::stoll(r.at("t_ns")), {}, {}, {}};
    const char* side[2] = {"left", "right"};
    for (int e = 0; e < 2; ++e) {
      const std::string s = side[e];
      const std::string state = r.at(s + "_state");
      t.confidence[e] = std::stof(r.at(s + "_confidence"));
      t.tracked[e] = state != "blink" && state != "lost" && t.confidence[e] > 0;
      t.dir[e] = m.pixel_to_direction(e == 0 ? Eye::left : Eye::right,
                                      {std::stof(r.at(s + "_x_px")), std::stof(r.at(s + "_y_px"))});
    }
    rows.push_back(t);
  }
  return rows;
}

/// One row of `foveal synth --truth`, on CLOCK_MONOTONIC through the foveald run's
/// summary.json (trace_t0_ns): the event, its index, each eye's true direction.
struct TruthRow {
  TimeNs t;
  std::string event;
  int index;
  glm::vec3 dir[2];
  glm::vec3 combined() const { return glm::normalize(dir[0] + dir[1]); }
};

inline std::vector<TruthRow> read_truth(const std::string& truth_csv, const std::string& foveald_dir) {
  const auto summary = nlohmann::json::parse(read_file(foveald_dir + "/summary.json"));
  const TimeNs t0 = summary["trace_t0_ns"].get<TimeNs>();
  std::vector<TruthRow> truth;
  for (const CsvRow& r : read_csv_rows(read_file(truth_csv)))
    truth.push_back({t0 + std::stoll(r.at("t_ns")), r.at("event"), std::stoi(r.at("event_index")),
                     {{std::stof(r.at("left_dir_x")), std::stof(r.at("left_dir_y")), std::stof(r.at("left_dir_z"))},
                      {std::stof(r.at("right_dir_x")), std::stof(r.at("right_dir_y")), std::stof(r.at("right_dir_z"))}}});
  return truth;
}

/// The latest row at or before t (the sample an app reading at t sees), or -1.
inline long row_at(const std::vector<TraceRow>& rows, TimeNs t) {
  long lo = -1;
  for (long i = 0; i < static_cast<long>(rows.size()) && rows[static_cast<std::size_t>(i)].t_ns <= t; ++i) lo = i;
  return lo;
}

/// Everything the two processes need, in one scratch folder.
class OpenXRRig {
 public:
  OpenXRRig() {
    static std::atomic<int> n{0};
    shm_ = "/foveal-xrtest-" + std::to_string(::getpid()) + "-" + std::to_string(n++);
    // foveald leaves its block behind when it exits (readers see the writer stopped), so
    // a block of this name can be a dead run's whose pid came round again: its fovea
    // would pass for this run's first one, and a FIFO could not be made in its place.
    ::shm_unlink(shm_.c_str());
    std::filesystem::create_directories(dir_.path("run"));
    std::filesystem::create_directories(dir_.path("config"));
  }
  ~OpenXRRig() { ::shm_unlink(shm_.c_str()); }
  OpenXRRig(const OpenXRRig&) = delete;
  OpenXRRig& operator=(const OpenXRRig&) = delete;
  std::string path(const std::string& p) const { return dir_.path(p); }
  const std::string& shm() const { return shm_; }

  std::vector<std::string> foveald_env() const {
    return {"XDG_RUNTIME_DIR=" + dir_.path("run"), "XDG_CONFIG_HOME=" + dir_.path("config"), "FOVEAL_SHM_NAME=" + shm_,
            "PATH=/usr/bin:/bin"};
  }
  /// The app's environment: Monado headless with its simulated HMD, the layer from
  /// `layers_share` (a share/ folder holding openxr/1/api_layers), core validation on.
  std::vector<std::string> app_env(const std::string& layers_share, const std::vector<std::string>& extra = {},
                                   bool validation = true) const {
    std::vector<std::string> env = {"XR_RUNTIME_JSON=" FOVEAL_TEST_OPENXR_RUNTIME,
                                    "XRT_COMPOSITOR_NULL=1",
                                    "SIMULATED_ENABLE=1",
                                    // /usr/share too: the Vulkan loader finds Mesa's drivers there.
                                    "XDG_DATA_DIRS=" + layers_share + ":/usr/share",
                                    "XDG_CONFIG_HOME=" + dir_.path("config"),
                                    "HOME=" + dir_.path(""),
                                    "FOVEAL_SHM_NAME=" + shm_,
                                    "PATH=/usr/bin:/bin"};
    if (validation && std::string(FOVEAL_TEST_OPENXR_VALIDATION_DIR).size() > 0) {
      env.push_back("XR_API_LAYER_PATH=" FOVEAL_TEST_OPENXR_VALIDATION_DIR);
      env.push_back("XR_ENABLE_API_LAYERS=XR_APILAYER_LUNARG_core_validation");
    }
    env.insert(env.end(), extra.begin(), extra.end());
    return env;
  }
  std::unique_ptr<Child> foveald(std::vector<std::string> args, const std::string& name) const {
    args.insert(args.begin(), bin("foveald"));
    return std::make_unique<Child>(args, foveald_env(), dir_.path(name + ".out"), dir_.path(name + ".err"));
  }
  std::unique_ptr<Child> app(std::vector<std::string> args, const std::vector<std::string>& env,
                             const std::string& name = "app") const {
    args.insert(args.begin(), bin("openxr_gaze"));
    return std::make_unique<Child>(args, env, dir_.path(name + ".out"), dir_.path(name + ".err"));
  }
  /// The quad-views example (examples/openxr_quad_views): EGL sessions, which Debian's
  /// core validation layer refuses (XrGraphicsBindingEGLMNDX), so it runs without it.
  std::unique_ptr<Child> quad_app(std::vector<std::string> args, const std::vector<std::string>& extra_env,
                                  const std::string& name, const std::string& layers_share) const {
    args.insert(args.begin(), bin("openxr_quad_views"));
    // Drawn from a head that stands still: the runtime's poses (Monado's simulated HMD
    // wobbles) are still located, reported and submitted, but the picture repeats, and no
    // frame meets the pose whose near-plane triangles kept llvmpipe busy for minutes once.
    args.push_back("--still");
    // Monado raises its compositor thread to SCHED_FIFO 99 where it may (root can): on a
    // loaded 2-core machine that starves the app and foveald. Without CAP_SYS_NICE it
    // stays an ordinary thread; nothing else changes.
    if (std::filesystem::exists("/usr/bin/setpriv"))
      args.insert(args.begin(), {"/usr/bin/setpriv", "--bounding-set=-sys_nice", "--inh-caps=-sys_nice"});
    return std::make_unique<Child>(args, app_env(layers_share, extra_env, /*validation=*/false), dir_.path(name + ".out"),
                                   dir_.path(name + ".err"));
  }
  std::vector<nlohmann::json> lines(const std::string& name = "app") const { return json_lines(read_file(dir_.path(name + ".out"))); }
  std::string err(const std::string& name = "app") const { return read_file(dir_.path(name + ".err")); }

 private:
  TempDir dir_;
  std::string shm_;
};

/// The openxr tests' fixture: skipped, by name, without a runtime; one rig per test.
class OpenXRTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (std::string(FOVEAL_TEST_OPENXR_RUNTIME).empty())
      GTEST_SKIP() << "no OpenXR runtime: scripts/build_monado.sh builds Monado from ../shared/vendor/monado";
  }
  /// Waits until foveald has published its block and its first fovea. The app could start
  /// earlier (it waits too), but then its first frames sit at the fixed place for as long
  /// as a loaded machine delays foveald's first sample, and a test that counts frames
  /// following the gaze would depend on that delay.
  void wait_for_block() const {
    eventually([&] { return first_fovea_published(); });
    ASSERT_TRUE(first_fovea_published()) << rig_.err("foveald");
  }
  bool first_fovea_published() const {
    auto shm = FoveaShm::open(rig_.shm());
    FoveaShmPayload fovea{};
    return shm && shm->read(fovea) && fovea.frame > 0;
  }

  OpenXRRig rig_;
};

}  // namespace foveal::test
