// `foveal bench merge` and `foveal filter-chart` against hostile input (issue 27, items 1-4):
// table names that would leave --out, a shell in --out, a full disk, crafted shard.json.
// foveal runs through cli::run_program (an argv, no shell), so --out reaches it verbatim.
#include <gtest/gtest.h>
#include <sys/mount.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "foveal/tools/run_program.hpp"
#include "other_user.hpp"
#include "sanitizers.hpp"
#include "test_support.hpp"

namespace foveal {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

const char* kHeader =
    "scene,method,sigma,shaded_samples,cost,gpu_ms,cpu_ms,shadow_ms,gbuffer_ms,mapping_ms,lighting_ms,inverse_ms,psnr_db,ssim,fpsnr_db";

// A 1/1 bench shard whose tables are `tables` (JSON text of the "tables" object).
std::string shard_json(const std::string& tables, const std::string& shard = "[1,1]", int points = 2,
                       const std::string& lists = R"({"rows":[[0,{"scene":"s"}],[1,{"scene":"s"}]]})") {
  return std::string(R"({"format":"foveal bench shard","version":1,"sweep":"--scenes s\n","kind":"bench","summary":{},)") +
         R"("rows":{"shard":)" + shard + R"(,"points":)" + std::to_string(points) + R"(,"tables":)" + tables +
         R"(,"lists":)" + lists + "}}";
}

// bench.csv with two rows; with `fgrid`, an empty fgrid.csv too (no charts then: the
// script charts an f grid only when it has points).
std::string bench_tables(bool fgrid = false) {
  return std::string(R"({"bench.csv":{"header":")") + kHeader +
         R"(","lines":[[0,"s,full,1,100,1,2,1,0,0,0,0,0,inf,1,inf"],[1,"s,rmfr,2.6,15,0.15,1,1,0,0,0,0,0,30,0.9,31"]]})" +
         (fgrid ? R"(,"fgrid.csv":{"header":"scene,sigma,fx,fy,fpsnr_db,psnr_db,ssim","lines":[]}})" : "}");
}
const char* kNoLines = R"({"bench.csv":{"header":"scene","lines":[]}})";

std::string make_shard(const TempDir& d, const std::string& name, const std::string& json) {
  fs::create_directories(d.path(name));
  test::write_file(d.path(name) + "/shard.json", json);
  return d.path(name);
}

// The 2 GiB cap on one run of foveal. ASan reserves terabytes of shadow address space at
// start, so under ASan the cap is its own allocation limit rather than RLIMIT_AS.
std::vector<std::string> memory_cap() {
#ifdef FOVEAL_TEST_ASAN
  const char* inherited = std::getenv("ASAN_OPTIONS");
  return {"/usr/bin/env", std::string("ASAN_OPTIONS=") + (inherited ? std::string(inherited) + ":" : std::string()) +
                              "max_allocation_size_mb=2048:allocator_may_return_null=1"};
#else
  return {"/usr/bin/prlimit", "--as=2147483648"};
#endif
}

// foveal with a 20 s deadline and a 2 GiB memory cap: the old code hung or allocated
// 8 GB here, and a test must end either way.
cli::ProgramRun foveal(std::vector<std::string> args) {
  std::vector<std::string> argv = {"/usr/bin/timeout", "-s", "KILL", "20"};
  for (auto& a : memory_cap()) argv.push_back(std::move(a));
  argv.push_back(test::bin("foveal"));
  argv.insert(argv.end(), args.begin(), args.end());
  auto r = cli::run_program(argv, {true, true});
  if (!r) ADD_FAILURE() << r.error().message;
  return r ? *r : cli::ProgramRun{};
}

std::vector<std::string> entries(const std::string& dir) {
  std::vector<std::string> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) out.push_back(e.path().filename().string());
  return out;
}

bool have_matplotlib() {
  auto r = cli::run_program({"/usr/bin/python3", "-c", "import matplotlib"}, {true, true});
  return r && r->ok();
}

TEST(BenchMergeInput, TableNamesOutsideTheKindsListAreRefusedNamingTheShard) {
  TempDir d;
  fs::create_directories(d.path("a/b"));
  const std::string out = d.path("a/b/out");
  const std::string row = R"({"header":"attacker header","lines":[[0,"attacker line"]]})";
  for (const std::string& name : {std::string("../../x"), d.path("absolute.csv"), std::string("evil.csv"), std::string("gaze.csv"),
                                  std::string("sub/bench.csv"), std::string(".."), std::string("")}) {
    SCOPED_TRACE(name);
    const std::string shard = make_shard(d, "s", shard_json("{\"" + name + "\":" + row + "}"));
    const auto r = foveal({"bench", "merge", "--no-png", "--out", out, shard});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(shard + "/shard.json: field 'rows.tables': '"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("is not a table of a 'bench' sweep"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << "nothing written, not even --out";
    EXPECT_FALSE(fs::exists(d.path("a/x")));
    EXPECT_FALSE(fs::exists(d.path("absolute.csv")));
  }
}

TEST(BenchMergeInput, AQuoteInOutRunsNoShell) {
  if (!have_matplotlib()) GTEST_SKIP() << "/usr/bin/python3 has no matplotlib: the charts cannot run";
  TempDir d;
  const std::string shard = make_shard(d, "s", shard_json(bench_tables()));
  const std::string out = d.path("x'; touch " + d.path("INJECTED") + "; echo '");
  const auto r = foveal({"bench", "merge", "--out", out, shard});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(d.path("INJECTED"))) << "a shell ran the --out text";
  for (const char* f : {"bench.csv", "bench.json", "pareto.png", "quality_cost.png", "table.md"})
    EXPECT_TRUE(fs::is_regular_file(out + "/" + f)) << f;
  EXPECT_EQ(entries(out).size(), 5u) << "no staging folder or temporary left";
}

TEST(FilterChartCli, AQuoteInOutRunsNoShell) {
  if (!have_matplotlib()) GTEST_SKIP() << "/usr/bin/python3 has no matplotlib: the charts cannot run";
  TempDir d;
  const std::string out = d.path("x'; touch " + d.path("INJECTED") + "; echo '");
  // The shipped recordings (the default --vive-dir): a missing folder is refused.
  const auto r = foveal({"filter-chart", "--seconds", "2", "--out", out});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(d.path("INJECTED"))) << "a shell ran the --out text";
  EXPECT_TRUE(fs::is_regular_file(out + "/filter_chart.png"));
  EXPECT_TRUE(fs::is_regular_file(out + "/filter_chart.csv"));
}

TEST(BenchMergeInput, ARefusedLaterTableLeavesNoEarlierOne) {
  TempDir d;
  const std::string shard = make_shard(d, "s", shard_json(bench_tables(true)));
  const std::string out = d.path("out");
  fs::create_directories(out + "/fgrid.csv");  // the second table's target is a directory
  const auto r = foveal({"bench", "merge", "--no-png", "--out", out, shard});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(out + "/fgrid.csv: is a directory"), std::string::npos) << r.err;
  EXPECT_EQ(entries(out), std::vector<std::string>{"fgrid.csv"}) << "bench.csv, bench.json or a staging folder left";
}

// A small tmpfs mounted on a temporary folder for the test (root only), unmounted again.
class SmallDisk {
 public:
  SmallDisk(const std::string& at, const std::string& size) : at_(at) {
    ok_ = ::mount("tmpfs", at.c_str(), "tmpfs", 0, ("size=" + size + ",mode=0755").c_str()) == 0;
  }
  ~SmallDisk() {
    if (ok_) ::umount2(at_.c_str(), MNT_DETACH);
  }
  bool ok() const { return ok_; }

 private:
  std::string at_;
  bool ok_ = false;
};

TEST(BenchMergeInput, AFullDiskLeavesNothingAndSaysTheDiskIsFull) {
  if (!test::is_root()) GTEST_SKIP() << "needs root to mount a small tmpfs; CI runs the tests as root";
  TempDir d;
  const std::string shard = make_shard(d, "s", shard_json(bench_tables()));
  const std::string disk = d.path("disk");
  fs::create_directories(disk);
  {  // Room for the tables and JSON, not for the charts (each PNG is tens of KB).
    SmallDisk small(disk, "24k");
    ASSERT_TRUE(small.ok()) << "mount tmpfs: " << std::strerror(errno);
    if (have_matplotlib()) {
      const auto r = foveal({"bench", "merge", "--out", disk, shard});
      EXPECT_EQ(r.exit_code, 2) << r.err;
      EXPECT_NE(r.err.find("ENOSPC: the disk is full"), std::string::npos) << r.err;
      EXPECT_EQ(r.err.find("matplotlib"), std::string::npos) << r.err;
      EXPECT_TRUE(entries(disk).empty()) << "left: " << (entries(disk).empty() ? "" : entries(disk).front());
    }
  }
  {  // No room at all: the tables themselves fail.
    SmallDisk small(disk, "8k");
    ASSERT_TRUE(small.ok());
    std::string filler(8192, 'x');
    { std::ofstream(disk + "/filler") << filler; }
    const auto r = foveal({"bench", "merge", "--no-png", "--out", disk, shard});
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("ENOSPC: the disk is full"), std::string::npos) << r.err;
    EXPECT_EQ(entries(disk), std::vector<std::string>{"filler"});
  }
}

// The chart script run by hand: each PNG and table.md is complete at its name or absent.
// 56k: pareto.png fits, quality_cost.png does not (the old script left it cut at 24 KB);
// 80k: both fit, table.md does not (the old script left table.md.tmp). The charts are
// about 36 KB each since they carry σ labels and the settings footer (60k before).
TEST(BenchCharts, AFullDiskLeavesNoPartialChartAndSaysSo) {
  if (!test::is_root()) GTEST_SKIP() << "needs root to mount a small tmpfs; CI runs the tests as root";
  if (!have_matplotlib()) GTEST_SKIP() << "/usr/bin/python3 has no matplotlib: the charts cannot run";
  for (const char* size : {"56k", "80k"}) {
    SCOPED_TRACE(size);
    TempDir d;
    const std::string disk = d.path("disk");
    fs::create_directories(disk);
    SmallDisk small(disk, size);
    ASSERT_TRUE(small.ok());
    test::write_file(disk + "/bench.csv", std::string(kHeader) + "\ns,full,1,100,1,2,1,0,0,0,0,0,inf,1,inf\n" +
                                              "s,rmfr,2.6,15,0.15,1,1,0,0,0,0,0,30,0.9,31\n");
    auto r = cli::run_program({"/usr/bin/python3", test::source_path("tools/charts/bench_charts.py"), disk}, {true, true});
    ASSERT_TRUE(r);
    EXPECT_EQ(r->exit_code, 1) << r->err;
    EXPECT_NE(r->err.find(": No space left on device (ENOSPC: the disk is full)"), std::string::npos) << r->err;
    EXPECT_EQ(r->err.find("Traceback"), std::string::npos) << r->err;
    for (const std::string& name : entries(disk)) {
      EXPECT_TRUE(name == "bench.csv" || name == "pareto.png" || name == "quality_cost.png") << name << " left";
      if (name.ends_with(".png")) {
        const std::string png = test::read_file(disk + "/" + name);
        EXPECT_TRUE(png.size() > 12 && png.compare(png.size() - 8, 4, "IEND") == 0) << name << " is cut at " << png.size() << " bytes";
      }
    }
  }
}

TEST(BenchMergeInput, CraftedShardFilesAreRefusedAtOnce) {
  TempDir d;
  const std::string out = d.path("out");
  struct Case {
    std::string name, expect;
  };
  // 200,000 deep: was SIGSEGV in nlohmann's recursive destructor.
  // (Otherwise a valid shard, so that the old code got as far as copying the summary.)
  make_shard(d, "deep", R"({"format":"foveal bench shard","version":1,"sweep":"","kind":"bench","summary":{"deep":)" +
                            std::string(200000, '[') + std::string(200000, ']') +
                            R"(},"rows":{"shard":[1,1],"points":0,"tables":{},"lists":{}}})");
  // N of 2e9: was an 8 GB vector, bad_alloc.
  make_shard(d, "huge_n", shard_json(kNoLines, "[1,2000000000]", 2, "{}"));
  // N of a million with one shard: the message names ten and counts the rest.
  make_shard(d, "million", shard_json(kNoLines, "[1,1000000]", 2000000, "{}"));
  // A FIFO with no writer: was a hang in open(2).
  fs::create_directories(d.path("fifo"));
  ASSERT_EQ(::mkfifo(d.path("fifo/shard.json").c_str(), 0600), 0);
  // A link to /dev/zero: read until memory ran out.
  fs::create_directories(d.path("zero"));
  fs::create_symlink("/dev/zero", d.path("zero/shard.json"));
  // Larger than the limit (sparse): refused from its size.
  fs::create_directories(d.path("big"));
  { std::ofstream(d.path("big/shard.json")); }
  fs::resize_file(d.path("big/shard.json"), (std::uintmax_t{64} << 20) + 1);
  const Case cases[] = {
      {"deep", "JSON nested deeper than 64 levels"},
      {"huge_n", "field 'shard': N must lie in 1..1000000"},
      {"million", "merge: shard 2/1000000, 3/1000000, 4/1000000, 5/1000000, 6/1000000, 7/1000000, 8/1000000, 9/1000000, "
                  "10/1000000, 11/1000000 and 999989 more missing"},
      {"fifo", "FIFO"},
      {"zero", "character device"},
      {"big", "64 MiB"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const auto r = foveal({"bench", "merge", "--no-png", "--out", out, d.path(c.name)});
    EXPECT_EQ(r.exit_code, 2) << cli::describe_end(r) << "\n" << r.err.substr(0, 2000);
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err.substr(0, 2000);
    if (c.name != "million") {
      EXPECT_NE(r.err.find(d.path(c.name) + "/shard.json"), std::string::npos) << r.err.substr(0, 2000);
    }
    EXPECT_LT(r.err.size(), 1000u);
    EXPECT_FALSE(fs::exists(out));
  }
}

// Issue 38, item 13: rows are copied into the merged CSV verbatim. A newline in a cell
// added rows, NUL and ESC reached the file, a text cell "=cmd|..." would run in a
// spreadsheet; each is refused naming the shard file, the table's line and the column.
TEST(BenchMergeInput, ControlCharactersAndFormulasInCellsAreRefusedNamingShardLineAndColumn) {
  TempDir d;
  const std::string out = d.path("out");
  const std::string good = "s,rmfr,2.6,15,0.15,1,1,0,0,0,0,0,30,0.9,31";
  struct Case {
    std::string name, line, expect;
  } cases[] = {
      {"newline", "s,full,1,100,1,2,1,0,0,0,0,0,inf,1,inf\ninjected,row,1,1,1,1,1,1,1,1,1,1,1,1,1",
       "bench.csv line 3, column 15 'fpsnr_db': a control character (0x0a, a newline) in the cell"},
      {"nul", std::string("s") + '\0' + "x,full,1,100,1,2,1,0,0,0,0,0,inf,1,inf", "bench.csv line 3, column 1 'scene': a control character (0x00, NUL)"},
      {"esc", "\x1b[31ms,full,1,100,1,2,1,0,0,0,0,0,inf,1,inf", "bench.csv line 3, column 1 'scene': a control character (0x1b, ESC)"},
      {"formula", "=cmd|' /C calc'!A0,full,1,100,1,2,1,0,0,0,0,0,inf,1,inf",
       "bench.csv line 3, column 1 'scene': the text cell starts with '=', which a spreadsheet would run as a formula"},
      {"at", "s,@SUM(A1),1,100,1,2,1,0,0,0,0,0,inf,1,inf", "bench.csv line 3, column 2 'method': the text cell starts with '@'"},
      {"minus", "s,full,-cmd,100,1,2,1,0,0,0,0,0,inf,1,inf", "bench.csv line 3, column 3 'sigma': the text cell starts with '-'"},
      {"plus", "+x,full,1,100,1,2,1,0,0,0,0,0,inf,1,inf", "column 1 'scene': the text cell starts with '+'"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const nlohmann::json tables = {{"bench.csv", {{"header", kHeader}, {"lines", {{0, good}, {1, c.line}}}}}};
    const std::string shard = make_shard(d, c.name, shard_json(tables.dump()));
    const auto r = foveal({"bench", "merge", "--no-png", "--out", out, shard});
    EXPECT_EQ(r.exit_code, 2) << cli::describe_end(r) << "\n" << r.err;
    EXPECT_NE(r.err.find(shard + "/shard.json: bench.csv line"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.expect), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out)) << "nothing written";
  }
  // A header cell too.
  const nlohmann::json bad_header = {{"bench.csv", {{"header", std::string(kHeader) + ",\x1b]0;x\x07"}, {"lines", nlohmann::json::array()}}}};
  const std::string shard = make_shard(d, "header", shard_json(bad_header.dump()));
  const auto r = foveal({"bench", "merge", "--no-png", "--out", out, shard});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(shard + "/shard.json: bench.csv header, column 16: a control character (0x1b, ESC)"), std::string::npos) << r.err;
}

// Numbers may start with a sign: only text cells are formulas.
TEST(BenchMergeInput, SignedNumbersAreNumbersAndTheReportCountsTheRowsWritten) {
  TempDir d;
  const std::string out = d.path("out");
  const nlohmann::json tables = {
      {"bench.csv", {{"header", kHeader}, {"lines", {{0, "s,full,1,100,1,2,1,0,0,0,0,0,inf,1,inf"}, {1, "s,rmfr,2.6,15,0.15,1,1,-0.5,+1e-3,0,0,0,-inf,0.9,31"}}}}}};
  // No "rows" list: the merge used to say "0 rows" after writing two.
  const std::string shard = make_shard(d, "s", shard_json(tables.dump(), "[1,1]", 2, "{}"));
  const auto r = foveal({"bench", "merge", "--no-png", "--out", out, shard});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("bench: 2 rows (bench.csv 2) -> " + out + "/bench.json"), std::string::npos) << r.out;
  EXPECT_NE(test::read_file(out + "/bench.csv").find("-0.5,+1e-3,0,0,0,-inf"), std::string::npos);
}

}  // namespace
}  // namespace foveal
