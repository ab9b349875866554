#include "foveal/bench/bench_outputs.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "foveal/core/data_paths.hpp"
#include "foveal/core/json_text.hpp"
#include "foveal/runtime/cli.hpp"
#include "foveal/tools/run_program.hpp"
#include "foveal/tools/staged_outputs.hpp"

namespace foveal::bench {

namespace {

constexpr const char* kPython = "/usr/bin/python3";

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

// Every table into the staging directory. Names come from the code or, in a merge, from
// shard files that read_shard held to their kind's list; StagedOutputs refuses any name
// that is not a plain file name as well.
Status write_tables(cli::StagedOutputs& out, const SweepRows& rows) {
  for (const std::string& file : rows.tables())
    if (Status s = out.write(file, rows.csv(file)); !s) return s;
  return {};
}

// The chart script on the staged files, run without a shell: the folder is one argv
// entry whatever it holds. Its PNGs and tables land in the staging directory too.
Status run_charts(const char* script, const cli::StagedOutputs& out) {
  const std::string path = data_path(script);
  auto r = cli::run_program({kPython, path, out.staging()});
  if (!r) return r.error();
  if (!r->ok())
    return io_error("charts: " + std::string(kPython) + " " + path + " ended with " + cli::describe_end(*r) +
                    " (its message is above); nothing was written");
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

Status check_charts_can_run() {
  auto r = cli::run_program({kPython, "-c", "import matplotlib"}, {true, true});
  if (r && r->ok()) return {};
  return bad_input(std::string("charts: ") + kPython + " cannot import matplotlib: install python3-matplotlib, or pass --no-png");
}

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
  if (kind == "gaze")
    if (nlohmann::json video = rows.list("video"); !video.empty()) summary["video"] = std::move(video);  // --gaze-video: bench_gaze.cpp
  // All or nothing: tables, JSON and charts are staged, then moved into `dir` together.
  auto out = cli::StagedOutputs::create(dir);
  if (!out) return fail(out.error());
  if (Status s = write_tables(*out, rows); !s) return fail(s.error());
  if (Status s = out->write(k->json_file, json_text(summary, 2) + "\n"); !s) return fail(s.error());
  if (charts)
    if (Status s = run_charts(k->charts, *out); !s) return fail(s.error());
  if (auto moved = out->commit(); !moved) return fail(moved.error());
  if (json) cli::print_json(summary);
  else {
    // The rows the tables got, each table's count: what was written, whatever the JSON lists hold.
    std::size_t total = 0;
    std::string each;
    for (const std::string& t : rows.tables()) {
      total += rows.lines(t);
      each += (each.empty() ? "" : ", ") + t + " " + std::to_string(rows.lines(t));
    }
    std::printf("bench: %zu rows (%s) -> %s/%s and its tables%s\n", total, each.c_str(), dir.c_str(), k->json_file,
                charts ? " and charts" : "");
  }
  return cli::kExitOk;
}

int write_shard(const std::string& dir, const SweepRows& rows, const nlohmann::json& summary, const std::string& sweep,
                const std::string& kind, bool json) {
  auto fail = [](const Error& e) { return cli::report(e); };
  const nlohmann::json file = {{"format", kShardFormat}, {"version", kShardVersion}, {"sweep", sweep}, {"kind", kind},
                               {"summary", summary}, {"rows", rows.to_json()}};
  auto out = cli::StagedOutputs::create(dir);
  if (!out) return fail(out.error());
  if (Status s = write_tables(*out, rows); !s) return fail(s.error());
  if (Status s = out->write("shard.json", json_text(file, 1) + "\n"); !s) return fail(s.error());
  if (auto moved = out->commit(); !moved) return fail(moved.error());
  const std::size_t own = rows.list("rows").size();
  if (json) cli::print_json({{"shard", rows.shard().text()}, {"points", rows.points()}, {"rows", own}, {"out", dir + "/shard.json"}});
  else
    std::printf("bench: shard %s of a sweep of %zu points: %zu rows -> %s/shard.json\n", rows.shard().text().c_str(), rows.points(),
                own, dir.c_str());
  return cli::kExitOk;
}

}  // namespace foveal::bench
