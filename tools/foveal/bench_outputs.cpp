#include "bench_outputs.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "foveal/core/atomic_file.hpp"
#include "foveal/core/data_paths.hpp"
#include "foveal/tools/cli.hpp"

namespace foveal::bench {

namespace {

constexpr const char* kShardFormat = "foveal bench shard";
constexpr int kShardVersion = 1;

struct Kind {
  const char* name;
  const char* json_file;
  const char* charts;  ///< under the data directory
};
constexpr Kind kKinds[] = {
    {"bench", "bench.json", "tools/charts/bench_charts.py"},
    {"gaze", "gaze.json", "tools/charts/gaze_charts.py"},
};

const Kind* find_kind(const std::string& name) {
  for (const Kind& k : kKinds)
    if (name == k.name) return &k;
  return nullptr;
}

double number(const nlohmann::json& v) { return v.is_string() ? INFINITY : v.get<double>(); }

// Each scene's automatic f against the best point of its f grid. The grid's points are
// points of the sweep of their own (other shards' perhaps), so the best point and the
// grid's cost are found here, from all of them: the same code for a run and a merge.
Result<nlohmann::json> auto_f_results(const SweepRows& rows) {
  auto is_num = [](const nlohmann::json& o, const char* k) { return o.contains(k) && o[k].is_number(); };
  const nlohmann::json grid = rows.list("fgrid_points");
  for (const nlohmann::json& g : grid)
    if (!g.is_object() || !is_num(g, "scene_index") || !is_num(g, "fx") || !is_num(g, "fy") || !is_num(g, "ms") ||
        !g.contains("fpsnr_db") || !(g["fpsnr_db"].is_number() || g["fpsnr_db"] == "inf"))
      return bad_input("fgrid_points: an item lacks scene_index, fx, fy, ms or fpsnr_db");
  nlohmann::json out = nlohmann::json::array();
  for (nlohmann::json a : rows.list("auto_f")) {
    if (!a.is_object() || !is_num(a, "scene_index") || !is_num(a, "auto_ms")) return bad_input("auto_f: an item lacks scene_index or auto_ms");
    double best = -INFINITY, best_fx = 0, best_fy = 0, grid_ms = 0;
    for (const nlohmann::json& g : grid) {
      if (g["scene_index"] != a["scene_index"]) continue;
      if (const double v = number(g["fpsnr_db"]); v > best) best = v, best_fx = g["fx"].get<double>(), best_fy = g["fy"].get<double>();
      grid_ms += g["ms"].get<double>();
    }
    a.erase("scene_index");
    a["grid_best_fx"] = best_fx;
    a["grid_best_fy"] = best_fy;
    a["grid_best_fpsnr_db"] = json_number(best);
    a["grid_ms"] = grid_ms;
    a["cost_ratio"] = a["auto_ms"].get<double>() / grid_ms;
    out.push_back(std::move(a));
  }
  return out;
}

Status write_tables(const std::string& dir, const SweepRows& rows) {
  for (const std::string& file : rows.tables())
    if (Status s = write_file_atomically(dir + "/" + file, rows.csv(file)); !s) return s;
  return {};
}

Status make_dir(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return io_error(dir + ": cannot create directory: " + ec.message());
  return {};
}

}  // namespace

std::string csv_number(double v) {
  std::ostringstream s;
  s.precision(6);
  s << v;
  return s.str();
}

nlohmann::json json_number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(csv_number(v)); }

int write_outputs(const std::string& dir, const SweepRows& rows, nlohmann::json summary, const std::string& kind, bool charts,
                  bool json) {
  auto fail = [](const Error& e) { return cli::report(e); };
  const Kind* k = find_kind(kind);
  if (!k) return fail(Error{ErrorKind::internal, "bench: no outputs of kind '" + kind + "'"});
  summary["rows"] = rows.list("rows");
  if (kind == "bench") {
    auto autos = auto_f_results(rows);
    if (!autos) return fail(autos.error());
    summary["auto_f"] = std::move(*autos);
    if (nlohmann::json flicker = rows.list("flicker"); !flicker.empty()) summary["flicker"] = std::move(flicker);  // bench_flicker.cpp
  }
  if (Status s = make_dir(dir); !s) return fail(s.error());
  if (Status s = write_tables(dir, rows); !s) return fail(s.error());
  if (Status s = write_file_atomically(dir + "/" + k->json_file, summary.dump(2) + "\n"); !s) return fail(s.error());
  if (charts) {
    const std::string cmd = "/usr/bin/python3 '" + data_path(k->charts) + "' '" + dir + "'";
    if (std::system(cmd.c_str()) != 0)
      return fail(io_error("charts: '" + cmd + "' failed (is python3-matplotlib installed?); the CSV and JSON files are written"));
  }
  if (json) cli::print_json(summary);
  else
    std::printf("bench: %zu rows -> %s/%s and its tables%s\n", summary["rows"].size(), dir.c_str(), k->json_file,
                charts ? " and charts" : "");
  return cli::kExitOk;
}

int write_shard(const std::string& dir, const SweepRows& rows, const nlohmann::json& summary, const std::string& sweep,
                const std::string& kind, bool json) {
  auto fail = [](const Error& e) { return cli::report(e); };
  const nlohmann::json file = {{"format", kShardFormat}, {"version", kShardVersion}, {"sweep", sweep}, {"kind", kind},
                               {"summary", summary}, {"rows", rows.to_json()}};
  if (Status s = make_dir(dir); !s) return fail(s.error());
  if (Status s = write_tables(dir, rows); !s) return fail(s.error());
  if (Status s = write_file_atomically(dir + "/shard.json", file.dump(1) + "\n"); !s) return fail(s.error());
  const std::size_t own = rows.list("rows").size();
  if (json) cli::print_json({{"shard", rows.shard().text()}, {"points", rows.points()}, {"rows", own}, {"out", dir + "/shard.json"}});
  else
    std::printf("bench: shard %s of a sweep of %zu points: %zu rows -> %s/shard.json\n", rows.shard().text().c_str(), rows.points(),
                own, dir.c_str());
  return cli::kExitOk;
}

Result<ShardFile> read_shard(const std::string& dir) {
  ShardFile f;
  f.path = dir + "/shard.json";
  std::ifstream in(f.path, std::ios::binary);
  if (!in) {
    if (!std::filesystem::is_directory(dir)) return bad_input(dir + ": no such directory");
    return bad_input(f.path + ": missing: not the output of `foveal bench --shard K/N`");
  }
  std::stringstream text;
  text << in.rdbuf();
  const nlohmann::json j = nlohmann::json::parse(text.str(), nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return bad_input(f.path + ": not valid JSON");
  if (!j.is_object() || !j.contains("format") || j["format"] != kShardFormat)
    return bad_input(f.path + ": field 'format': not a bench shard file");
  if (!j.contains("version") || j["version"] != kShardVersion)
    return bad_input(f.path + ": field 'version': expected " + std::to_string(kShardVersion) + " (written by another foveal version?)");
  if (!j.contains("sweep") || !j["sweep"].is_string()) return bad_input(f.path + ": field 'sweep': expected a string");
  if (!j.contains("kind") || !j["kind"].is_string() || !find_kind(j["kind"].get<std::string>())) {
    std::string known;
    for (const Kind& k : kKinds) known += std::string(known.empty() ? "" : ", ") + k.name;
    return bad_input(f.path + ": field 'kind': expected one of " + known);
  }
  if (!j.contains("summary") || !j["summary"].is_object()) return bad_input(f.path + ": field 'summary': expected an object");
  auto rows = SweepRows::from_json(j.contains("rows") ? j["rows"] : nlohmann::json(), f.path);
  if (!rows) return rows.error();
  f.sweep = j["sweep"].get<std::string>();
  f.kind = j["kind"].get<std::string>();
  f.summary = j["summary"];
  f.rows = std::move(*rows);
  return f;
}

}  // namespace foveal::bench
