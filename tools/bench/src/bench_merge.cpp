#include "foveal/bench/bench_merge.hpp"

#include <algorithm>
#include <sstream>

#include "foveal/bench/bench_outputs.hpp"
#include "foveal/core/json_text.hpp"
#include "foveal/runtime/cli.hpp"

namespace foveal::bench {

namespace {

// A value from a shard file, cut short: messages never print unbounded input.
std::string shown(std::string s) {
  constexpr std::size_t kMax = 120;
  if (s.size() > kMax) s = s.substr(0, kMax) + "...";
  return s;
}

// The first option line where two sweeps differ, for the message.
std::string first_difference(const std::string& a, const std::string& b) {
  std::istringstream ia(a), ib(b);
  std::string la, lb;
  while (true) {
    const bool more_a = static_cast<bool>(std::getline(ia, la)), more_b = static_cast<bool>(std::getline(ib, lb));
    if (!more_a && !more_b) return "";
    if (!more_a) la.clear();
    if (!more_b) lb.clear();
    if (la != lb) return "'" + shown(lb) + "' against '" + shown(la) + "'";
  }
}

}  // namespace

int run_merge(const MergeOptions& a) {
  auto fail = [](const Error& e) { return cli::report(e); };
  std::vector<bench::ShardFile> files;
  for (const std::string& dir : a.shards) {
    auto f = bench::read_shard(dir);
    if (!f) return fail(f.error());
    if (!files.empty() && f->kind != files.front().kind)
      return fail(bad_input(f->path + ": a part of a '" + f->kind + "' sweep, " + files.front().path + " of a '" + files.front().kind + "' one"));
    if (!files.empty() && f->sweep != files.front().sweep)
      return fail(bad_input(f->path + ": not the same sweep as " + files.front().path + ": " + first_difference(files.front().sweep, f->sweep)));
    files.push_back(std::move(*f));
  }
  std::vector<bench::SweepRows> parts;
  std::vector<std::string> names;
  for (const auto& f : files) parts.push_back(f.rows), names.push_back(f.path);
  auto merged = bench::SweepRows::merge(parts, names);
  if (!merged) return fail(merged.error());
  // The run's facts from the first shard; memory and wall time the largest of any shard.
  nlohmann::json summary = files.front().summary;
  for (const char* most : {"peak_rss_mb", "wall_s"}) {
    double v = 0;
    for (const auto& f : files)
      if (f.summary.contains(most) && f.summary[most].is_number()) v = std::max(v, f.summary[most].get<double>());
    if (summary.contains(most)) summary[most] = v;
  }
  for (const auto& f : files) {
    if (f.summary.value("renderer", nlohmann::json()) != summary.value("renderer", nlohmann::json()))
      cli::warn(f.path + ": rendered on '" + shown(json_text(f.summary.value("renderer", nlohmann::json()))) + "', " + files.front().path +
                " on '" + shown(json_text(summary.value("renderer", nlohmann::json()))) + "': the timing columns mix machines");
  }
  summary["shards"] = files.size();
  return bench::write_outputs(a.out, *merged, summary, files.front().kind, !a.no_png, a.json);
}

}  // namespace foveal::bench
