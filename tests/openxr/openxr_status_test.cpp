// `foveal openxr` against hostile input (docs/bad-input.md, round 3): layer and runtime
// manifests with fields of the wrong type, a runtime that crashes or hangs when the
// loader loads it (tests/openxr/hostile_runtime.cpp), a FIFO or non-JSON file as the
// runtime manifest, no runtime at all; and the probe's output, kept out of sight unless
// asked for (-v) or the probe failed. Each run is a real `foveal` process in an
// environment of its own; the tests wait for its exit, with a generous guard.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "test_support.hpp"

namespace foveal {
namespace {

using json = nlohmann::json;

constexpr int kGuardMs = 120'000;  // far past any probe's limit: only a hang reaches it

struct CliRun {
  int exit_code = -1;  // -1: still running at the guard (then killed)
  std::string out, err;
};

class OpenXRStatusCli : public ::testing::Test {
 protected:
  void SetUp() override {
    for (const char* d : {"config", "etcxdg", "data", "share", "run"}) std::filesystem::create_directories(dir_.path(d));
  }

  /// `foveal openxr ARGS` with only this test's folders on the loader's search paths.
  CliRun foveal_openxr(const std::vector<std::string>& args, const std::vector<std::string>& extra_env = {}) {
    std::vector<std::string> argv = {test::bin("foveal"), "openxr"};
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<std::string> env = {"HOME=" + dir_.path(), "XDG_CONFIG_HOME=" + dir_.path("config"),
                                    "XDG_CONFIG_DIRS=" + dir_.path("etcxdg"), "XDG_DATA_HOME=" + dir_.path("data"),
                                    "XDG_DATA_DIRS=" + dir_.path("share"), "XDG_RUNTIME_DIR=" + dir_.path("run"),
                                    "FOVEAL_SHM_NAME=/foveal-test-xrstatus-" + std::to_string(::getpid()),
                                    "PATH=/usr/bin:/bin"};
    for (const std::string& x : extra_env) {  // an extra VAR=VALUE replaces the base one
      const std::string key = x.substr(0, x.find('=') + 1);
      std::erase_if(env, [&](const std::string& b) { return b.rfind(key, 0) == 0; });
      env.push_back(x);
    }
    std::vector<char*> a, e;
    for (auto& s : argv) a.push_back(s.data());
    a.push_back(nullptr);
    for (auto& s : env) e.push_back(s.data());
    e.push_back(nullptr);
    const std::string out = dir_.path("out.txt"), err = dir_.path("err.txt");
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&fa, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    pid_t pid = -1;
    const int rc = ::posix_spawn(&pid, a[0], &fa, nullptr, a.data(), e.data());
    posix_spawn_file_actions_destroy(&fa);
    CliRun r;
    if (rc != 0) return r;
    r.exit_code = test::wait_for_exit(pid, kGuardMs);
    if (r.exit_code < 0) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, nullptr, 0);
    }
    r.out = test::read_file(out);
    r.err = test::read_file(err);
    return r;
  }

  /// A runtime manifest naming the hostile runtime.
  std::string hostile_manifest() {
    const std::string p = dir_.path("hostile_runtime.json");
    test::write_file(p, json{{"file_format_version", "1.0.0"},
                             {"runtime", {{"name", "hostile"}, {"library_path", FOVEAL_TEST_HOSTILE_RUNTIME}}}}
                            .dump());
    return p;
  }

  test::TempDir dir_;
};

TEST_F(OpenXRStatusCli, ManifestFieldsOfTheWrongTypeAreReportedAsBrokenNamingFileAndField) {
  const std::string layers = dir_.path("data/openxr/1/api_layers");
  std::filesystem::create_directories(layers + "/implicit.d");
  std::filesystem::create_directories(layers + "/explicit.d");
  const std::string implicit = layers + "/implicit.d/XrApiLayer_foveal_gaze.json";
  const std::string expl = layers + "/explicit.d/XrApiLayer_foveal_gaze.json";
  test::write_file(implicit, R"({"file_format_version":"1.0.0","api_layer":{"name":5,"library_path":"x.so"}})");
  test::write_file(expl,
                   R"({"file_format_version":"1.0.0","api_layer":{"name":"XR_APILAYER_FOVEAL_gaze","library_path":["a"]}})");
  const std::string rt = dir_.path("runtime.json");
  test::write_file(rt, R"({"file_format_version":"1.0.0","runtime":{"library_path":["a"]}})");

  const CliRun r = foveal_openxr({"--json"}, {"XR_RUNTIME_JSON=" + rt});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const json j = json::parse(r.out, nullptr, false);
  ASSERT_TRUE(j.is_object()) << r.out;
  const json& m = j["layer"]["manifests"];
  ASSERT_EQ(m.size(), 2u) << j.dump(2);
  EXPECT_EQ(m[0]["problem"], implicit + ": api_layer.name is a number, not a string") << j.dump(2);
  EXPECT_EQ(m[1]["problem"], expl + ": api_layer.library_path is an array, not a string") << j.dump(2);
  EXPECT_FALSE(j["layer"]["enabled"].get<bool>());
  EXPECT_NE(j["layer"]["why"].get<std::string>().find("broken"), std::string::npos) << j.dump(2);
  EXPECT_EQ(j["runtime"]["problem"], rt + ": runtime.library_path is an array, not a string") << j.dump(2);
  EXPECT_NE(j["verdict"].get<std::string>().find("manifest is unusable"), std::string::npos) << j.dump(2);

  const CliRun text = foveal_openxr({}, {"XR_RUNTIME_JSON=" + rt});
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("implicit, broken: " + implicit + ": api_layer.name is a number"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("unusable: " + rt + ": runtime.library_path is an array"), std::string::npos) << text.out;
}

TEST_F(OpenXRStatusCli, ARuntimeThatCrashesIsReportedWithItsSignalAndTheEndOfItsOutput) {
  const CliRun r = foveal_openxr({}, {"XR_RUNTIME_JSON=" + hostile_manifest(), "FOVEAL_TEST_RUNTIME_MODE=crash"});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("probe: the runtime crashed (signal 11"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("=> the runtime failed when probed (the runtime crashed (signal 11"), std::string::npos) << r.out;
  // On failure the output's last lines are shown (they say why), not all of it.
  EXPECT_NE(r.out.find("hostile runtime: line 30\n"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("hostile runtime: line 1\n"), std::string::npos) << r.out;
  EXPECT_EQ(r.err.find("hostile runtime"), std::string::npos) << r.err;

  const CliRun j = foveal_openxr({"--json"}, {"XR_RUNTIME_JSON=" + hostile_manifest(), "FOVEAL_TEST_RUNTIME_MODE=crash"});
  ASSERT_EQ(j.exit_code, 0) << j.err;
  const json doc = json::parse(j.out, nullptr, false);
  ASSERT_TRUE(doc.is_object()) << j.out;
  EXPECT_TRUE(doc["runtime"]["failed"].get<bool>());
  EXPECT_FALSE(doc["runtime"]["probed"].get<bool>());
}

TEST_F(OpenXRStatusCli, ARuntimeThatHangsIsStoppedAtTheTimeLimit) {
  const std::string pidfile = dir_.path("runtime.pid");
  const CliRun r = foveal_openxr({"--probe-timeout", "2"}, {"XR_RUNTIME_JSON=" + hostile_manifest(),
                                                          "FOVEAL_TEST_RUNTIME_MODE=hang",
                                                          "FOVEAL_TEST_RUNTIME_PIDFILE=" + pidfile});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("probe: the runtime did not answer in 2 s"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("=> the runtime failed when probed"), std::string::npos) << r.out;
  // The probe's process is gone with the command: nothing is left hanging.
  const std::string pid_text = test::read_file(pidfile);
  if (!pid_text.empty()) {
    const pid_t pid = static_cast<pid_t>(std::stoi(pid_text));
    EXPECT_TRUE(::kill(pid, 0) == -1 && errno == ESRCH) << "the probe's process " << pid << " still runs";
  }
}

TEST_F(OpenXRStatusCli, AFifoOrNonJsonRuntimeManifestIsNamedForWhatItIs) {
  const std::string fifo = dir_.path("runtime.fifo");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const CliRun r = foveal_openxr({}, {"XR_RUNTIME_JSON=" + fifo});
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("unusable: " + fifo + ": OpenXR runtime manifest is a FIFO"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("library is missing"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("=> the runtime's manifest is unusable"), std::string::npos) << r.out;

  const std::string text = dir_.path("runtime.txt");
  test::write_file(text, "not json at all\n");
  const CliRun t = foveal_openxr({}, {"XR_RUNTIME_JSON=" + text});
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_NE(t.out.find("unusable: " + text + ": not valid JSON"), std::string::npos) << t.out;
  EXPECT_EQ(t.out.find("library is missing"), std::string::npos) << t.out;
}

TEST_F(OpenXRStatusCli, NoRuntimeFoundSaysSoAndKeepsTheLoadersOutputOutOfSight) {
  for (const char* p : {"/etc/openxr/1/active_runtime.json", "/etc/openxr/1/active_runtime.x86_64.json"}) {
    std::error_code ec;
    if (std::filesystem::exists(p, ec)) GTEST_SKIP() << p << " exists on this machine: a runtime is always found";
  }
  const CliRun r = foveal_openxr({});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("runtime: none found"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("=> no OpenXR runtime found: OpenXR apps cannot start here"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("foveald's gaze\n"), std::string::npos) << r.out;
  EXPECT_EQ(r.err, "") << "the loader's messages belong to the probe's output";
}

TEST_F(OpenXRStatusCli, AWorkingRuntimesOutputIsShownOnlyWithVerbose) {
  const std::string monado = FOVEAL_TEST_OPENXR_RUNTIME;
  if (monado.empty()) GTEST_SKIP() << "no OpenXR runtime built (scripts/build_monado.sh)";
  // /usr/share: the Vulkan loader finds Mesa's drivers there, which Monado's null compositor needs.
  const std::vector<std::string> env = {"XR_RUNTIME_JSON=" + monado, "XRT_COMPOSITOR_NULL=1", "SIMULATED_ENABLE=1",
                                        "XDG_DATA_DIRS=" + dir_.path("share") + ":/usr/share"};
  const CliRun quiet = foveal_openxr({}, env);
  ASSERT_EQ(quiet.exit_code, 0) << quiet.out << quiet.err;
  EXPECT_NE(quiet.out.find("own eye gaze"), std::string::npos) << quiet.out;  // probed
  EXPECT_EQ(quiet.out.find("the probe's output"), std::string::npos) << quiet.out;
  EXPECT_EQ(quiet.err, "");
  const CliRun verbose = foveal_openxr({"-v"}, env);
  ASSERT_EQ(verbose.exit_code, 0) << verbose.err;
  EXPECT_NE(verbose.out.find("the probe's output:\n"), std::string::npos) << verbose.out;
  EXPECT_GT(verbose.out.size(), quiet.out.size());
}

}  // namespace
}  // namespace foveal
