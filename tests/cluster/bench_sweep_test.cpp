// The sweep's parts (tools/bench/src/bench_sweep.cpp) without rendering: which shard runs
// which point, rows kept in point order, the shard file's round trip and its refusals,
// and merges that are refused.
#include <gtest/gtest.h>

#include "foveal/bench/bench_sweep.hpp"

using foveal::bench::parse_shard;
using foveal::bench::Shard;
using foveal::bench::SweepRows;

namespace {

// A grid of `points` points, each adding one line "p<I>" and one item I.
SweepRows run(Shard s, std::size_t points) {
  SweepRows r(s);
  r.table("t.csv", "h");
  for (std::size_t i = 0; i < points; ++i)
    if (r.take()) {
      r.add_line("t.csv", "p" + std::to_string(i));
      r.add_item("items", i);
    }
  return r;
}

std::vector<SweepRows> shards(int n, std::size_t points) {
  std::vector<SweepRows> out;
  for (int k = 1; k <= n; ++k) out.push_back(run({k, n}, points));
  return out;
}

const std::vector<std::string> kNames = {"a", "b", "c", "d", "e"};

}  // namespace

TEST(BenchSweep, ParsesShardSpecsAndRefusesBadOnes) {
  auto s = parse_shard("3/8");
  ASSERT_TRUE(s);
  EXPECT_EQ(s->k, 3);
  EXPECT_EQ(s->n, 8);
  for (const char* bad : {"0/4", "5/4", "1/0", "x", "2/", "/4", "1/4/2", "-1/4", "1.5/4", ""}) {
    auto b = parse_shard(bad);
    ASSERT_FALSE(b) << bad;
    EXPECT_NE(b.error().message.find("--shard"), std::string::npos);
  }
}

TEST(BenchSweep, ShardsRunDisjointPointsCoveringTheGrid) {
  const auto parts = shards(4, 10);
  std::size_t lines = 0;
  for (const auto& p : parts) {
    EXPECT_EQ(p.points(), 10u);
    lines += p.lines("t.csv");
  }
  EXPECT_EQ(lines, 10u);
  EXPECT_EQ(parts[1].csv("t.csv"), "h\np1\np5\np9\n");  // round robin: 2/4 runs 1, 5, 9
  EXPECT_EQ(run({3, 4}, 2).csv("t.csv"), "h\n");        // a shard without a point still has the table
}

TEST(BenchSweep, AMergeInAnyOrderEqualsTheWholeRun) {
  const SweepRows whole = run({}, 11);
  auto parts = shards(4, 11);
  std::swap(parts[0], parts[3]);
  auto m = SweepRows::merge(parts, kNames);
  ASSERT_TRUE(m) << m.error().message;
  EXPECT_EQ(m->csv("t.csv"), whole.csv("t.csv"));
  EXPECT_EQ(m->list("items"), whole.list("items"));
  EXPECT_EQ(m->points(), 11u);
}

TEST(BenchSweep, RowsAddedOutOfPointOrderAreKeptInIt) {
  // A frame-major experiment: take every point first, then add rows frame by frame.
  SweepRows r;
  r.table("f.csv", "h");
  std::size_t p[3];
  for (auto& i : p) ASSERT_TRUE(r.take(&i));
  for (int frame = 0; frame < 2; ++frame)
    for (std::size_t i : p) r.add_line("f.csv", std::to_string(i) + "@" + std::to_string(frame), i);
  EXPECT_EQ(r.csv("f.csv"), "h\n0@0\n0@1\n1@0\n1@1\n2@0\n2@1\n");
}

TEST(BenchSweep, TheShardFileRoundTripsAndRefusesForeignPoints) {
  const SweepRows s = run({2, 3}, 7);
  auto back = SweepRows::from_json(s.to_json(), "x/shard.json");
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(back->to_json(), s.to_json());
  nlohmann::json j = s.to_json();
  j["tables"]["t.csv"]["lines"].push_back({std::size_t{0}, "p0"});  // point 0 is shard 1/3's
  auto foreign = SweepRows::from_json(j, "x/shard.json");
  ASSERT_FALSE(foreign);
  EXPECT_NE(foreign.error().message.find("x/shard.json: field 'tables.t.csv.lines': point 0 is not one of shard 2/3's"),
            std::string::npos)
      << foreign.error().message;
  for (const char* field : {"shard", "points", "tables", "lists"}) {
    nlohmann::json broken = s.to_json();
    broken[field] = "?";
    auto r = SweepRows::from_json(broken, "x/shard.json");
    ASSERT_FALSE(r) << field;
    EXPECT_NE(r.error().message.find(std::string("field '") + field), std::string::npos) << r.error().message;
  }
}

TEST(BenchSweep, MergesOfMissingTwiceOrForeignShardsAreRefused) {
  auto missing = shards(4, 9);
  missing.erase(missing.begin() + 2);
  auto r = SweepRows::merge(missing, kNames);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("shard 3/4 missing"), std::string::npos) << r.error().message;

  auto twice = shards(3, 9);
  twice.push_back(twice[1]);
  r = SweepRows::merge(twice, kNames);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("d: shard 2/3 is given twice (also b)"), std::string::npos) << r.error().message;

  auto other_n = shards(2, 9);
  other_n.push_back(run({3, 3}, 9));
  r = SweepRows::merge(other_n, kNames);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("c: shard 3/3 of a sweep in 3 parts"), std::string::npos) << r.error().message;

  auto other_grid = shards(2, 9);
  other_grid[1] = run({2, 2}, 8);
  r = SweepRows::merge(other_grid, kNames);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("b: a sweep of 8 points"), std::string::npos) << r.error().message;
}
